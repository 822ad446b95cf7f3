#!/usr/bin/env bash
# Tests of tools/plot_run.py and of the plots 'wsntrack run' draws.
# Usage: plot_test.sh BIN_DIR SOURCE_DIR WORK_DIR CASE
#   script   the script alone on a tiny hand-written run directory (no DDS)
#   run      'wsntrack run' with and without --no-plot, SVG, a random layout, no matplotlib
# Exit 77 (skipped) when /usr/bin/python3 has no matplotlib: there is nothing to draw with.
set -uo pipefail
bin="$1"; src="$2"; work="$3"; case_name="$4"
python=/usr/bin/python3
plot="$bin/plot_run.py"
rm -rf "$work/$case_name"; mkdir -p "$work/$case_name"; cd "$work/$case_name" || exit 1

fail() { echo "FAIL: $*" >&2; exit 1; }

[ -x "$python" ] && "$python" -c "import matplotlib" 2>/dev/null || { echo "SKIP: no matplotlib for $python"; exit 77; }
[ -f "$plot" ] || fail "$plot missing: the build should copy tools/plot_run.py next to wsntrack"
cmp -s "$plot" "$src/tools/plot_run.py" || fail "$plot differs from $src/tools/plot_run.py (stale copy)"
# The package the script is an entry point over, copied beside bin/ (it looks for ../python).
(cd "$src/python" && find wsntrack -name '*.py' -not -path '*/__pycache__/*') | while read -r name; do
  cmp -s "$src/python/$name" "$bin/../python/$name" || fail "$bin/../python/$name differs from $src/python/$name (stale copy)"
done || exit 1

is_png() { [ "$(head -c 8 "$1" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ]; }
is_svg() { head -c 2000 "$1" | grep -q "<svg"; }
check_pngs() {
  for name in tracks cardinality ospa; do
    [ -s "$1/$name.png" ] || fail "$1/$name.png missing"
    is_png "$1/$name.png" || fail "$1/$name.png does not start with the PNG signature"
  done
}

# A python without matplotlib, simulated: a package of that name that cannot be imported.
mkdir -p fakepy/matplotlib
echo 'raise ImportError("simulated: no matplotlib")' >fakepy/matplotlib/__init__.py

case "$case_name" in
  script)
    # A 20 x 10 grid, two supernodes (one boundary at x = 10), two targets, three tracks.
    mkdir -p run
    cat >run/scenario.yaml <<'EOF'
# wsntrack resolved scenario (a small hand-made one)
name: "tiny"
region:
  x_min: 0
  y_min: 0
  x_max: 20
  y_max: 10
sensors:
  layout: grid
  spacing: 1
  count: 10000
targets:
  scripted:
    - {appear_tick: 1, disappear_tick: 0, x: 1, y: 1, vx: 1, vy: 0.5}
supernodes:
  - {x: 5, y: 5}
  - {x: 15, y: 5}
tracker:
  engine: "gnn"
  params: {}
metrics:
  ospa_c: 5
  ospa_p: 2
run:
  ticks: 10
  seed: 3
EOF
    {
      echo "tick,target,x,y,vx,vy"
      for t in $(seq 1 10); do
        echo "$t,0,$t.000000,$((1 + t / 2)).000000,1.000000,0.500000"
        [ "$t" -ge 4 ] && echo "$t,1,$((20 - t)).500000,8.000000,-1.000000,0.000000"
      done
    } >run/truth.csv
    {
      echo "tick,track,x,y,vx,vy"
      for t in $(seq 2 10); do
        echo "$t,281474976710657,$t.100000,$((1 + t / 2)).200000,1.000000,0.500000"
        [ "$t" -ge 6 ] && [ "$t" -ne 8 ] && echo "$t,562949953421313,$((20 - t)).300000,7.800000,-1.000000,0.000000"
        [ "$t" -eq 5 ] && echo "$t,844424930131969,3.000000,9.000000,0.000000,0.000000"
      done
    } >run/tracks.csv
    printf '{\n  "metrics": {\n    "first_tick": 1,\n    "eps_k": 0.25,\n    "ospa_mean": 1.5,\n    "ospa_per_tick": [5, 0.1, 0.1, 5, 5, 0.2, 0.2, 2.5, 0.3, 0.3]\n  },\n  "timing": {"wall_s": 0.1}\n}\n' \
      >run/metrics.json
    printf '{\n  "run_id": "00ff",\n  "domain": 7,\n  "ticks": 10,\n  "status": "complete"\n}\n' >run/run.json

    "$python" "$plot" --help >help.txt || fail "--help failed"
    grep -q "tracks.FORMAT" help.txt && grep -q "Exit status" help.txt || fail "--help does not explain the outputs"

    "$python" "$plot" run >out.txt 2>err.txt || { cat err.txt >&2; fail "plot of a good run directory failed"; }
    check_pngs run/plots
    "$python" "$plot" run --format svg --out "$PWD/svg" >/dev/null 2>err.txt || { cat err.txt >&2; fail "svg failed"; }
    for name in tracks cardinality ospa; do is_svg "svg/$name.svg" || fail "svg/$name.svg is not SVG"; done
    # SVG keeps its text as text: the OSPA source and the legend can be checked.
    grep -q "from metrics.json" svg/ospa.svg || fail "ospa.svg does not say it read metrics.json"
    grep -q "true target path" svg/tracks.svg || fail "tracks.svg lacks its legend"
    grep -q "tracking-group boundary" svg/tracks.svg || fail "tracks.svg draws no tracking-group boundary"

    # Only a complete run is drawn (run.json's status); --allow-incomplete stamps every figure.
    grep -q "INCOMPLETE RUN" svg/*.svg && fail "a complete run's plots are stamped INCOMPLETE RUN"
    rm -rf failed; cp -r run failed; rm -rf failed/plots
    printf '{\n  "run_id": "00ff",\n  "status": "failed",\n  "reason": "supernode 2 killed by SIGKILL"\n}\n' \
      >failed/run.json
    "$python" "$plot" failed --out "$PWD/failed-plots" >/dev/null 2>err.txt
    code=$?
    [ "$code" -eq 2 ] || { cat err.txt >&2; fail "a failed run: exit $code, expected 2"; }
    grep -q "failed: incomplete run (status failed: supernode 2 killed by SIGKILL)" err.txt \
      || { cat err.txt >&2; fail "a failed run: not refused with its status and reason"; }
    [ -e failed-plots ] && fail "a failed run: plots were drawn"
    for state in '"status": "running"' '"run_id": "00ff"'; do  # still running; no status (an older wsntrack)
      printf '{\n  %s\n}\n' "$state" >failed/run.json
      "$python" "$plot" failed --out "$PWD/failed-plots" >/dev/null 2>err.txt && fail "run.json {$state}: drawn"
      grep -q "failed: incomplete run (status " err.txt || { cat err.txt >&2; fail "run.json {$state}: message"; }
    done
    rm failed/run.json
    "$python" "$plot" failed >/dev/null 2>err.txt && fail "no run.json: drawn"
    grep -q "failed: incomplete run (status missing: no run.json" err.txt || { cat err.txt >&2; fail "no run.json: message"; }
    printf '{\n  "status": "failed",\n  "reason": "timed out after 3 s"\n}\n' >failed/run.json
    "$python" "$plot" failed --allow-incomplete --format svg --out "$PWD/failed-svg" >/dev/null 2>err.txt \
      || { cat err.txt >&2; fail "--allow-incomplete failed"; }
    grep -q "warning: .*incomplete run (status failed: timed out after 3 s)" err.txt || fail "--allow-incomplete: no warning"
    for name in tracks cardinality ospa; do
      grep -q "INCOMPLETE RUN" "failed-svg/$name.svg" \
        || fail "failed-svg/$name.svg is not stamped INCOMPLETE RUN"
      grep -q "timed out after 3 s" "failed-svg/$name.svg" || fail "failed-svg/$name.svg does not give the reason"
    done

    # --wait (how wsntrack runs it): nothing before the word to go, nothing at all without it.
    echo go | "$python" "$plot" run --wait --out "$PWD/waited" >/dev/null 2>err.txt || { cat err.txt >&2; fail "--wait"; }
    check_pngs waited
    "$python" "$plot" run --wait --out "$PWD/not-waited" </dev/null >/dev/null 2>err.txt \
      || { cat err.txt >&2; fail "--wait without go: not exit 0"; }
    [ -e not-waited ] && fail "--wait without go drew plots"

    # metrics_per_tick.csv, when present, is preferred to metrics.json.
    {
      echo "tick,truth_targets,tracks,ospa,gospa,gospa_localisation,gospa_missed,gospa_false"
      for t in $(seq 1 10); do echo "$t,1,1,0.5,0.5,0.5,0,0"; done
    } >run/metrics_per_tick.csv
    "$python" "$plot" run --format svg --out "$PWD/svg2" >/dev/null 2>err.txt || { cat err.txt >&2; fail "per-tick csv"; }
    grep -q "from metrics_per_tick.csv" svg2/ospa.svg || fail "metrics_per_tick.csv was not used"

    # tracks.csv with the label and covariance columns (read by name) draws like the older one.
    "$python" -B "$src/tests/tools/tiny_run.py" newer || fail "tiny_run.py"
    "$python" "$plot" newer --out "$PWD/newer-plots" >/dev/null 2>err.txt || { cat err.txt >&2; fail "newer tracks.csv"; }
    check_pngs newer-plots

    # Class evidence (tracks.csv's class and class_probability, truth.csv's class): tracks.png colours
    # the tracks by the class declared at each tick. Track 0:1 has no class at ticks 2-3, then
    # wheeled_light, then wheeled_heavy; 1:1 is human; g5 never has a class.
    "$python" -B "$src/tests/tools/tiny_run.py" classes || fail "tiny_run.py classes"
    add_classes() {  # DIR: appends the class columns to DIR's tracks.csv and truth.csv
      awk -F, -v OFS=, 'NR == 1 { print $0, "class", "class_probability"; next }
        $3 == "0:1" && $1 >= 7 { print $0, "wheeled_heavy", "0.810000"; next }
        $3 == "0:1" && $1 >= 4 { print $0, "wheeled_light", "0.550000"; next }
        $3 == "1:1" { print $0, "human", "0.700000"; next }
        { print $0, "", "" }' "$1/tracks.csv" >"$1/tracks.csv.new" && mv "$1/tracks.csv.new" "$1/tracks.csv"
      awk -F, -v OFS=, 'NR == 1 { print $0, "class"; next } { print $0, ($2 == 0 ? "wheeled_heavy" : "human") }' \
        "$1/truth.csv" >"$1/truth.csv.new" && mv "$1/truth.csv.new" "$1/truth.csv"
    }
    add_classes classes
    [ "$(head -1 classes/tracks.csv | tr ',' '\n' | tail -2 | tr '\n' ' ')" = "class class_probability " ] \
      || fail "tiny run with classes: header"
    "$python" "$plot" classes --out "$PWD/classes-plots" >/dev/null 2>err.txt || { cat err.txt >&2; fail "class columns"; }
    check_pngs classes-plots
    "$python" "$plot" classes --format svg --out "$PWD/classes-svg" >/dev/null 2>err.txt \
      || { cat err.txt >&2; fail "class columns, svg"; }
    for entry in "track declared wheeled_light" "track declared wheeled_heavy" "track declared human" \
                 "track, no class yet" "4–10 human" "1–10 wheeled_heavy"; do
      grep -q "$entry" classes-svg/tracks.svg || fail "classes-svg/tracks.svg lacks '$entry'"
    done
    grep -q "one colour per track" classes-svg/tracks.svg && fail "classes-svg/tracks.svg: coloured per track"
    grep -q "track declared tracked" classes-svg/tracks.svg && fail "classes-svg/tracks.svg: a class not present"
    # Older runs, and class columns that are all empty, draw exactly as before: one colour per track.
    "$python" -B "$src/tests/tools/tiny_run.py" old --old || fail "tiny_run.py --old"
    "$python" "$plot" old --format svg --out "$PWD/old-svg" >/dev/null 2>err.txt || { cat err.txt >&2; fail "old tracks.csv"; }
    grep -q "one colour per track" old-svg/tracks.svg || fail "old-svg/tracks.svg is not coloured per track"
    grep -q "track declared" old-svg/tracks.svg && fail "old-svg/tracks.svg has class entries"
    "$python" -B "$src/tests/tools/tiny_run.py" noclass || fail "tiny_run.py noclass"
    sed -i '1s/$/,class,class_probability/; 2,$s/$/,,/' noclass/tracks.csv
    sed -i '1s/$/,class/; 2,$s/$/,unknown/' noclass/truth.csv
    "$python" "$plot" noclass --out "$PWD/noclass-plots" >/dev/null 2>err.txt || { cat err.txt >&2; fail "empty classes"; }
    cmp -s noclass-plots/tracks.png newer-plots/tracks.png || fail "empty class columns changed tracks.png"

    # A sensors.csv is drawn whatever the layout says.
    printf 'sensor,x,y\n0,1.5,2.5\n1,17.25,3.75\n' >run/sensors.csv
    "$python" "$plot" run --out "$PWD/withsensors" >/dev/null 2>err.txt || { cat err.txt >&2; fail "with sensors.csv"; }
    check_pngs withsensors

    # Typed sensors (sensors.layout list, sensor_model field_sensors): a marker and a colour per type,
    # each sensor's coverage (a sector of its range and field of view, a disc for 360 degrees), and a
    # legend entry per type present with its number of sensors; an untyped entry stays a plain dot.
    rm -rf typed; mkdir typed; cp run/truth.csv run/tracks.csv run/metrics.json run/run.json typed/
    cat >typed/scenario.yaml <<'EOF'
# wsntrack resolved scenario (a small hand-made one, with typed sensors)
name: "tiny typed"
region:
  x_min: 0
  y_min: 0
  x_max: 20
  y_max: 10
sensors:
  layout: list
  count: 6
  list:
    - {name: "radar1", type: "radar", x: 1, y: 1, heading: 45, range: 9}
    - {name: "pir1", type: "pir", x: 19, y: 5, heading: 180}
    - {name: "cam1", type: "camera", x: 10, y: 9.5, heading: -90, fov: 40}
    - {name: "cam2", type: "camera", x: 5, y: 0.5, heading: 90, range: 3}
    - {name: "ant1", type: "acoustic_antenna", x: 15, y: 2, heading: 0}
    - {name: "plain", x: 12, y: 6}
sensor_model:
  kind: "field_sensors"
  pir: {range: 6, fov_deg: 10}
  camera: {range: 4, fov_deg: 30}
  acoustic_antenna: {range: 2.5, fov_deg: 360}
supernodes:
  - {x: 5, y: 5}
  - {x: 15, y: 5}
tracker:
  engine: "sbmht"
  params: {}
metrics:
  ospa_c: 5
  ospa_p: 2
run:
  ticks: 10
  seed: 3
EOF
    printf 'sensor,x,y\n0,1,1\n1,19,5\n2,10,9.5\n3,5,0.5\n4,15,2\n5,12,6\n' >typed/sensors.csv
    "$python" "$plot" typed --out "$PWD/typed-plots" >/dev/null 2>err.txt || { cat err.txt >&2; fail "typed sensors"; }
    check_pngs typed-plots
    "$python" "$plot" typed --format svg --out "$PWD/typed-svg" >/dev/null 2>err.txt \
      || { cat err.txt >&2; fail "typed sensors, svg"; }
    for entry in "radar (1)" "pir (1)" "camera (2)" "acoustic_antenna (1)" ">sensor<"; do
      grep -q "$entry" typed-svg/tracks.svg || fail "typed-svg/tracks.svg lacks the legend entry '$entry'"
    done
    for entry in "magnetic (" "acoustic_beacon ("; do
      grep -q "$entry" typed-svg/tracks.svg && fail "typed-svg/tracks.svg: an entry for a type not present ('$entry')"
    done
    # Without types, or with another sensor model, a list draws as it always did: plain dots only.
    for variant in untyped otherkind; do
      rm -rf "$variant"; cp -r typed "$variant"; rm -rf "$variant/plots"
    done
    sed -i 's/ type: "[a-z_]*",//' untyped/scenario.yaml
    sed -i 's/^  kind: "field_sensors"$/  kind: "signal_strength"/' otherkind/scenario.yaml
    for variant in untyped otherkind; do
      "$python" "$plot" "$variant" --format svg --out "$PWD/$variant-svg" >/dev/null 2>err.txt \
        || { cat err.txt >&2; fail "$variant list"; }
      grep -q ">sensor<" "$variant-svg/tracks.svg" || fail "$variant-svg/tracks.svg lacks the plain sensor entry"
      grep -Eq "(radar|pir|camera) \(" "$variant-svg/tracks.svg" && fail "$variant-svg/tracks.svg has sensor-type entries"
    done
    grep -Eq "(radar|pir|camera) \(" svg/tracks.svg && fail "svg/tracks.svg (a grid) has sensor-type entries"
    # Malformed typed sensors: FILE:LINE: what was expected (line 12 is radar1, 13 pir1).
    rm -rf t1 t2 t3 t4
    for d in t1 t2 t3 t4; do cp -r typed "$d"; rm -rf "$d/plots"; done
    sed -i '13s/type: "pir"/type: "sonar"/' t1/scenario.yaml
    sed -i '12s/range: 9/range: -5/' t2/scenario.yaml
    sed -i '13s/heading: 180/heading: west/' t3/scenario.yaml
    sed -i 's/^  camera: {range: 4, fov_deg: 30}$/  camera: {range: 4, fov_deg: 0}/' t4/scenario.yaml

    # Bad input: exit 2, FILE[:LINE]: what was expected, and never a traceback.
    expect_bad() {
      local dir="$1" pattern="$2"
      "$python" "$plot" "$dir" >/dev/null 2>err.txt
      local code=$?
      [ "$code" -eq 2 ] || { cat err.txt >&2; fail "$dir: exit $code, expected 2"; }
      grep -Eq "$pattern" err.txt || { cat err.txt >&2; fail "$dir: message lacks /$pattern/"; }
      grep -q "Traceback" err.txt && { cat err.txt >&2; fail "$dir: traceback"; }
      return 0
    }
    bad() { rm -rf "$1"; cp -r run "$1"; rm -rf "$1/plots" "$1/metrics_per_tick.csv" "$1/sensors.csv"; }
    bad b1; sed -i '4s/.*/4,281474976710657,abc,1.0,0,0/' b1/tracks.csv
    expect_bad b1 "b1/tracks.csv:4: column 'x' must be a number, got 'abc'"
    bad b2; sed -i '3s/.*/2,0,1.0/' b2/truth.csv
    expect_bad b2 "b2/truth.csv:3: expected 6 fields \(tick,target,x,y,vx,vy\), got 3"
    bad b3; sed -i '1s/.*/tick,id,x,y/' b3/tracks.csv
    expect_bad b3 "b3/tracks.csv:1: expected the header 'tick,track,label,x,y,.*' \(or the older 'tick,track,x,y,vx,vy'\), got 'tick,id,x,y' \(no column 'track'\)"
    bad b4; rm b4/truth.csv
    expect_bad b4 "b4/truth.csv: missing"
    # PyYAML meets the unterminated flow mapping of line 6 at the ':' of line 7.
    bad b5; sed -i 's/^  x_max: 20$/  x_max: {oops/' b5/scenario.yaml
    expect_bad b5 "b5/scenario.yaml:7: expected ',' or '\\}', but got ':' \\(while parsing a flow mapping at line 6\\)"
    bad b12; sed -i 's/^  ticks: 10$/\tticks: 10/' b12/scenario.yaml
    expect_bad b12 "b12/scenario.yaml:25: found character '.t' that cannot start any token"
    bad b13; printf '# a list, not a scenario\n- 1\n' >b13/scenario.yaml
    expect_bad b13 "b13/scenario.yaml:2: expected a mapping at the top level"
    bad b6; sed -i 's/^  ticks: 10$/  ticks: many/' b6/scenario.yaml
    expect_bad b6 "b6/scenario.yaml:25: 'run.ticks' must be a number, got 'many'"
    bad b11; sed -i 's/^  - {x: 15, y: 5}$/  - {x: 15, y: north}/' b11/scenario.yaml
    expect_bad b11 "b11/scenario.yaml:17: supernodes\[1\].y must be a number, got 'north'"
    bad b7; echo '{"metrics": ' >b7/metrics.json
    expect_bad b7 "b7/metrics.json:2: malformed JSON"
    bad b8; : >b8/tracks.csv
    expect_bad b8 "b8/tracks.csv:1: expected the header .* got an empty file"
    bad b9; printf 'tick,truth_targets,tracks,ospa,gospa,gospa_localisation,gospa_missed,gospa_false\n1,1,1,x,0,0,0,0\n' \
      >b9/metrics_per_tick.csv
    expect_bad b9 "b9/metrics_per_tick.csv:2: column 'ospa' must be a number, got 'x'"
    bad b10; sed -i '5s/.*/3,281474976710657,nan,1.0,0,0/' b10/tracks.csv
    expect_bad b10 "b10/tracks.csv:5: column 'x' must be finite"
    expect_bad "$PWD/nonexistent" "nonexistent: not a directory"
    # Bad class columns (on copies of the run with classes; tracks.csv line 5 is tick 5 of 0:1, wheeled_light).
    bad_class() { rm -rf "$1"; cp -r classes "$1"; rm -rf "$1/plots"; }
    bad_class c1; sed -i '5s/,wheeled_light,/,tank,/' c1/tracks.csv
    expect_bad c1 "c1/tracks.csv:5: column 'class' must be empty or one of wheeled_light, wheeled_heavy, tracked, human, group, aerial, got 'tank'"
    bad_class c2; sed -i '5s/,0\.550000$/,/' c2/tracks.csv
    expect_bad c2 "c2/tracks.csv:5: column 'class_probability' must be set exactly when 'class' is"
    bad_class c3; sed -i '5s/,0\.550000$/,1.5/' c3/tracks.csv
    expect_bad c3 "c3/tracks.csv:5: column 'class_probability' must be in \[0, 1\], got '1.5'"
    bad_class c4; sed -i '1s/,class_probability$/,probability/' c4/tracks.csv
    expect_bad c4 "c4/tracks.csv:1: expected both columns 'class' and 'class_probability' or neither, got only 'class'"
    bad_class c5; sed -i '3s/,wheeled_heavy$/,Tank/' c5/truth.csv
    expect_bad c5 "c5/truth.csv:3: column 'class' must be one of unknown, wheeled_light, .*, got 'Tank'"
    expect_bad t1 "t1/scenario.yaml:13: sensors.list\[1\].type must be one of acoustic_antenna, acoustic_beacon, magnetic, pir, radar, camera, got 'sonar'"
    expect_bad t2 "t2/scenario.yaml:12: sensors.list\[0\].range must be in \[0, 1e6\] \(0: the type's\), got -5"
    expect_bad t3 "t3/scenario.yaml:13: sensors.list\[1\].heading must be a number, got 'west'"
    expect_bad t4 "t4/scenario.yaml:21: 'sensor_model.camera.fov_deg' must be a number in \(0, 360\], got '0'"
    "$python" "$plot" run --format gif >/dev/null 2>err.txt; [ $? -eq 2 ] || fail "--format gif accepted"

    # Without matplotlib: exit 3 and one clear line.
    PYTHONPATH="$PWD/fakepy" "$python" "$plot" run --out "$PWD/nompl-out" >/dev/null 2>err.txt
    code=$?
    [ "$code" -eq 3 ] || { cat err.txt >&2; fail "without matplotlib: exit $code, expected 3"; }
    grep -q "matplotlib is not available" err.txt || { cat err.txt >&2; fail "without matplotlib: message"; }
    [ -e nompl-out ] && fail "without matplotlib: an output directory was created"

    # Without PyYAML: the same, naming the package to install.
    mkdir -p fakeyaml/yaml
    echo 'raise ImportError("simulated: no PyYAML")' >fakeyaml/yaml/__init__.py
    PYTHONPATH="$PWD/fakeyaml" "$python" "$plot" run --out "$PWD/noyaml-out" >/dev/null 2>err.txt
    code=$?
    [ "$code" -eq 3 ] || { cat err.txt >&2; fail "without PyYAML: exit $code, expected 3"; }
    grep -q "PyYAML is not available .*apt-get install python3-yaml" err.txt || { cat err.txt >&2; fail "without PyYAML: message"; }
    grep -q "Traceback" err.txt && { cat err.txt >&2; fail "without PyYAML: traceback"; }
    [ -e noyaml-out ] && fail "without PyYAML: an output directory was created"
    PYTHONPATH="$PWD/fakeyaml" "$python" "$plot" --animate run --out "$PWD/noyaml.gif" --quiet >/dev/null 2>err.txt
    code=$?
    [ "$code" -eq 3 ] || { cat err.txt >&2; fail "--animate without PyYAML: exit $code, expected 3"; }
    grep -q "PyYAML is not available" err.txt || { cat err.txt >&2; fail "--animate without PyYAML: message"; }
    echo "ok" ;;

  run)
    wsntrack="$bin/wsntrack"
    scenario="$src/scenarios/oh_quadrants.yaml"
    run() {
      local out="$1"; shift
      timeout 300 "$wsntrack" run "$scenario" --quiet --ticks 20 --out "$PWD/$out" "$@" >"$out.stdout" 2>"$out.stderr"
    }
    run_ok() { run "$@" || { cat "$1.stderr" >&2; fail "run $*"; }; }

    run_ok png --seed 4
    check_pngs png/plots
    grep -Eq "^  plots +.*png/plots/\{tracks,cardinality,ospa\}\.png \([0-9.]+ s\)$" png.stdout \
      || { cat png.stdout >&2; fail "the summary does not report the plots"; }
    [ -s png/logs/plot.log ] || fail "no logs/plot.log"
    [ -e png/sensors.csv ] && fail "sensors.csv written for a grid layout"

    run_ok noplot --seed 4 --no-plot
    [ -e noplot/plots ] && fail "--no-plot drew plots"
    grep -q "^  plots " noplot.stdout && fail "--no-plot: the summary mentions plots"
    cmp -s png/tracks.csv noplot/tracks.csv || fail "plotting changed the run's outputs"

    run_ok svg --seed 4 --plot-format svg
    for name in tracks cardinality ospa; do is_svg "svg/plots/$name.svg" || fail "svg/plots/$name.svg is not SVG"; done
    run_ok pdf --seed 4 --plot-format pdf
    for name in tracks cardinality ospa; do
      [ "$(head -c 5 "pdf/plots/$name.pdf")" = "%PDF-" ] || fail "pdf/plots/$name.pdf is not PDF"
    done

    run bad --plot-format gif && fail "--plot-format gif accepted"
    grep -q "plot-format must be png, svg or pdf" bad.stderr || { cat bad.stderr >&2; fail "--plot-format message"; }
    [ -e bad ] && fail "a bad --plot-format created a run directory"

    # A random layout: sensors.csv holds every sensor, and the plot draws them.
    run_ok random --seed 5 --set sensors.layout=random --set sensors.count=3000
    [ "$(head -1 random/sensors.csv)" = "sensor,x,y" ] || fail "sensors.csv header"
    [ "$(wc -l <random/sensors.csv)" -eq 3001 ] || fail "sensors.csv should have 3000 rows"
    check_pngs random/plots

    # No matplotlib: the run still succeeds, with one warning line and the summary saying so.
    PYTHONPATH="$PWD/fakepy" run_ok nompl --seed 4
    [ -e nompl/plots ] && fail "plots without matplotlib?"
    [ "$(grep -c "warning: no plots: matplotlib is not available" nompl.stderr)" -eq 1 ] \
      || { cat nompl.stderr >&2; fail "no single warning line without matplotlib"; }
    grep -Eq "^  plots +none: matplotlib is not available" nompl.stdout || { cat nompl.stdout >&2; fail "summary"; }
    echo "ok" ;;

  *) fail "unknown case $case_name" ;;
esac
