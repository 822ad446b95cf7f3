#!/usr/bin/env bash
# Integration tests of the live view: `wsntrack watch` and examples/watch_tracks.c against real
# clusters on loopback, and `wsntrack run --tick-interval`.
# Usage: watch_test.sh BIN_DIR SOURCE_DIR WORK_DIR CASE
# Every process a case starts is waited for by its own PID with a deadline, and killed by that
# PID when the deadline passes; each case ends by checking that no process of its runs is left.
set -uo pipefail
bin="$1"; src="$2"; work="$3"; case_name="$4"
wsntrack="$bin/wsntrack"
example="$bin/watch_tracks"
scenario="$src/scenarios/oh_quadrants.yaml"
rm -rf "${work:?}/$case_name"; mkdir -p "$work/$case_name"; cd "$work/$case_name" || exit 1

started_pids=()
fail() {
  echo "FAIL: $*" >&2
  for pid in "${started_pids[@]}"; do kill -9 "$pid" 2>/dev/null; done
  exit 1
}

# Waits up to $2 seconds for process $1 (a child of this shell) to exit and sets $rc to its exit
# status; on the deadline kills it (TERM, then KILL) and fails the test.
wait_bounded() {
  local pid="$1" seconds="$2" what="$3" tenths=$(( $2 * 10 ))
  while kill -0 "$pid" 2>/dev/null && [ "$tenths" -gt 0 ]; do sleep 0.1; tenths=$(( tenths - 1 )); done
  if kill -0 "$pid" 2>/dev/null; then
    kill -TERM "$pid" 2>/dev/null; sleep 2; kill -KILL "$pid" 2>/dev/null; wait "$pid" 2>/dev/null
    fail "$what (pid $pid) still running after $seconds s"
  fi
  wait "$pid"; rc=$?
}

# Waits up to 30 s for the launcher to write $1/run.json.
wait_for_run_json() {
  local tenths=300
  while [ ! -f "$1/run.json" ] && [ "$tenths" -gt 0 ]; do sleep 0.1; tenths=$(( tenths - 1 )); done
  [ -f "$1/run.json" ] || fail "$1/run.json did not appear within 30 s"
}

json_value() { sed -n "s/.*\"$2\": \"\{0,1\}\([0-9a-f]*\)\"\{0,1\},\{0,1\}$/\1/p" "$1/run.json"; }

# shellcheck source=common.sh
. "$(dirname "$0")/common.sh"

case "$case_name" in
  live)
    # A paced run, watched from its start by `wsntrack watch --plain` and by the C example.
    ticks=60
    "$wsntrack" run "$scenario" --seed 5 --ticks "$ticks" --tick-interval 0.05 --quiet --no-plot --out "$PWD/paced" \
      >run.stdout 2>run.stderr & launcher=$!; started_pids+=("$launcher")
    wait_for_run_json "$PWD/paced"
    domain=$(json_value "$PWD/paced" domain); run_id=$(json_value "$PWD/paced" run_id)
    last_viewer=$(sed -n 's/.*"viewer_participant_indices": \[[0-9]*, \([0-9]*\)\].*/\1/p' "$PWD/paced/run.json")
    [ -n "$domain" ] && [ -n "$run_id" ] && [ -n "$last_viewer" ] || { cat "$PWD/paced/run.json" >&2; fail "run.json lacks domain, run_id or viewer slots"; }
    "$wsntrack" watch "$PWD/paced" --plain --timeout 60 >watch.out 2>watch.err & watcher=$!; started_pids+=("$watcher")
    # run.json marks the directory as the run's before its inputs are written; the configuration
    # the example reads is written last (after the credentials it names), and whole.
    for _ in $(seq 1 300); do [ -f "$PWD/paced/cyclonedds.xml" ] && break; sleep 0.1; done
    [ -f "$PWD/paced/cyclonedds.xml" ] || fail "paced/cyclonedds.xml did not appear within 30 s"
    CYCLONEDDS_URI="file://$PWD/paced/cyclonedds.xml" WSN_PARTICIPANT_INDEX="$last_viewer" \
      "$example" "$domain" "$run_id" 60 >example.out 2>example.err & viewer=$!; started_pids+=("$viewer")
    wait_bounded "$launcher" 120 "wsntrack run"; [ "$rc" -eq 0 ] || { cat run.stderr >&2; fail "paced run exited $rc"; }
    wait_bounded "$watcher" 30 "wsntrack watch"; [ "$rc" -eq 0 ] || { cat watch.err >&2; fail "watch exited $rc"; }
    wait_bounded "$viewer" 30 "watch_tracks"; [ "$rc" -eq 0 ] || { cat example.err >&2; fail "watch_tracks exited $rc"; }

    # The frames: increasing ticks up to the last, the metrics of TickMetrics, and the last
    # tick's tracks exactly those of tracks.csv.
    python3 - "$PWD/paced" watch.out example.out "$ticks" <<'EOF' || fail "watch output does not match the run (above)"
import csv, re, sys
run_dir, watch_out, example_out, ticks = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
problems = []
def expect(ok, what):
    if not ok: problems.append(what)

def decode(compact):  # S:N, S:tTsK[.J] or gN, as wsntrack watch shows ids (common/track_id.hpp)
    if compact.startswith("g"): return int(compact[1:])
    supernode, serial = compact.split(":")
    birth = re.fullmatch(r"t(\d+)s(\d+)(?:\.(\d+))?", serial)
    serial = (int(birth[3] or 0) << 44 | int(birth[1]) << 24 | int(birth[2])) if birth else int(serial)
    return ((int(supernode) + 1) << 48) | serial

truth = {}  # tick -> targets
for row in csv.DictReader(open(f"{run_dir}/truth.csv")):
    truth[int(row["tick"])] = truth.get(int(row["tick"]), 0) + 1
last_tracks = {int(r["track"]): (float(r["x"]), float(r["y"]))
               for r in csv.DictReader(open(f"{run_dir}/tracks.csv")) if int(r["tick"]) == ticks}
# tracks.csv names each track as the watch does.
for r in csv.DictReader(open(f"{run_dir}/tracks.csv")):
    expect(decode(r["label"]) == int(r["track"]), f"tracks.csv label {r['label']} does not name track {r['track']}")

def same_tracks(shown, where):
    expect(set(shown) == set(last_tracks), f"{where}: track ids {sorted(shown)} != tracks.csv {sorted(last_tracks)}")
    for track, (x, y) in shown.items():
        if track in last_tracks:
            tx, ty = last_tracks[track]
            expect(abs(x - tx) <= 0.006 and abs(y - ty) <= 0.006, f"{where}: track {track} at ({x}, {y}), tracks.csv ({tx}, {ty})")

frames, frame = [], None
lines = open(watch_out).read().splitlines()
for line in lines:
    m = re.match(r"^tick (\d+)/(\d+)  (.*)$", line)
    if m:
        frame = {"tick": int(m[1]), "of": int(m[2]), "head": dict(kv.split("=") for kv in m[3].split()), "rows": {}}
        frames.append(frame)
    elif frame is not None and line.startswith("  ") and not line.split()[0] == "track":
        fields = line.split()
        frame["rows"][decode(fields[0])] = (float(fields[1]), float(fields[2]))
    elif not line:
        frame = None
ticks_shown = [f["tick"] for f in frames]
expect(len(frames) >= 20, f"only {len(frames)} frames of a {ticks}-tick run at 20 ticks/s")
expect(all(a < b for a, b in zip(ticks_shown, ticks_shown[1:])), f"frame ticks not increasing: {ticks_shown}")
expect(ticks_shown and ticks_shown[-1] == ticks, f"last frame is tick {ticks_shown[-1:]} not {ticks}")
expect(all(f["of"] == ticks for f in frames), "a frame does not say t/T with T = the run's ticks")
expect(any(l.startswith("the run finished") for l in lines), "no final 'the run finished' line")
if frames:
    last = frames[-1]
    same_tracks(last["rows"], "watch, last frame")
    expect(last["head"]["K"] == str(len(last["rows"])), f"K={last['head']['K']} but {len(last['rows'])} rows")
    expect(last["head"]["K*"] == str(truth.get(ticks, 0)), f"K*={last['head']['K*']}, truth.csv has {truth.get(ticks, 0)}")
    expect(re.fullmatch(r"[0-9.]+", last["head"]["OSPA"]) is not None, f"no OSPA in the last frame: {last['head']}")

# The C example: one line per tick, in order, ending with the last tick and DONE.
example = open(example_out).read().splitlines()
tick_lines = [l for l in example if l.startswith("tick=")]
example_ticks = [int(re.match(r"tick=(\d+)", l)[1]) for l in tick_lines]
expect(len(tick_lines) >= ticks // 2, f"watch_tracks printed {len(tick_lines)} tick lines")
expect(all(a + 1 == b for a, b in zip(example_ticks, example_ticks[1:])), f"watch_tracks ticks not consecutive: {example_ticks}")
expect(example_ticks and example_ticks[-1] == ticks, f"watch_tracks' last tick is {example_ticks[-1:]}")
expect(example and example[-1] == f"done at tick {ticks}", f"watch_tracks' last line: {example[-1:]}")
if tick_lines:
    shown = {int(t): (float(x), float(y)) for t, x, y in re.findall(r"(\d+)@\((-?[0-9.]+),(-?[0-9.]+)\)", tick_lines[-1])}
    same_tracks(shown, "watch_tracks, last line")
    expect(f"K*={truth.get(ticks, 0)} " in tick_lines[-1], f"watch_tracks' last line lacks K*={truth.get(ticks, 0)}")

for p in problems: print("  " + p, file=sys.stderr)
sys.exit(1 if problems else 0)
EOF

    # Pacing only changes the timing: the tick loop took about T - 1 intervals, and every
    # output is byte-identical to an unpaced run's. The loop is timed from the aggregator's end of
    # tick 1, by which the sources may already be run.max_ticks_in_flight paced ticks ahead.
    python3 - "$PWD/paced/metrics.json" "$ticks" "$PWD/paced/scenario.yaml" <<'EOF' || fail "the paced run was not paced"
import re, sys
wall = float(re.search(r'"wall_s": ([0-9.]+)', open(sys.argv[1]).read())[1])
in_flight = int(re.search(r"max_ticks_in_flight: (\d+)", open(sys.argv[3]).read())[1])
least = (int(sys.argv[2]) - 1 - in_flight) * 0.05 * 0.95
if wall < least: sys.exit(f"tick loop took {wall} s, at least {least} s expected")
EOF
    timeout 300 "$wsntrack" run "$scenario" --seed 5 --ticks "$ticks" --quiet --no-plot --out "$PWD/unpaced" \
      >unpaced.stdout 2>unpaced.stderr || { cat unpaced.stderr >&2; fail "unpaced run"; }
    for f in tracks.csv tracks_supernode.csv observations.csv truth.csv network.json scenario.yaml; do
      cmp -s "paced/$f" "unpaced/$f" || fail "$f differs between the paced and the unpaced run"
    done
    diff <(grep -v -e '"timing"' -e '"provenance"' paced/metrics.json) \
         <(grep -v -e '"timing"' -e '"provenance"' unpaced/metrics.json) >/dev/null \
      || fail "metrics.json differs between the paced and the unpaced run"
    no_leftovers ;;

  not_a_run)
    # A missing or empty directory may be where a run is about to start: the watch waits for it
    # (--timeout), then exits 1 saying why.
    "$wsntrack" watch "$PWD/does-not-exist" --timeout 1 >out.txt 2>err.txt; rc=$?
    [ "$rc" -eq 1 ] || fail "watch on a missing directory exited $rc, expected 1 after its timeout"
    grep -q "no run started in .*does-not-exist within 1 s: .*no such directory" err.txt \
      || { cat err.txt >&2; fail "unclear message for a missing directory"; }
    mkdir empty-dir
    "$wsntrack" watch "$PWD/empty-dir" --timeout 1 >out.txt 2>err.txt; rc=$?
    [ "$rc" -eq 1 ] || fail "watch on an empty directory exited $rc, expected 1 after its timeout"
    grep -q "is empty: no run has started there yet" err.txt || { cat err.txt >&2; fail "unclear message for an empty directory"; }
    # Not a run directory: a clear message and exit 2, at once, without touching DDS.
    : >a-file
    "$wsntrack" watch "$PWD/a-file" --timeout 30 >out.txt 2>err.txt; rc=$?
    [ "$rc" -eq 2 ] || fail "watch on a file exited $rc, expected 2"
    mkdir plain-dir; echo hello >plain-dir/notes.txt
    "$wsntrack" watch "$PWD/plain-dir" --timeout 30 >out.txt 2>err.txt; rc=$?
    [ "$rc" -eq 2 ] || fail "watch on a non-run directory exited $rc, expected 2"
    grep -q "not a wsntrack run directory" err.txt || { cat err.txt >&2; fail "unclear message for a non-run directory"; }
    "$wsntrack" watch >out.txt 2>err.txt; rc=$?
    [ "$rc" -eq 2 ] || fail "watch without RUN_DIR exited $rc, expected 2"
    "$wsntrack" watch --help >out.txt 2>&1 || fail "watch --help failed"
    grep -q "Exit status" out.txt || fail "watch --help does not explain the exit status"
    for bad in "--timeout 0" "--timeout nan" "--max-fps 0" "--bogus"; do
      # shellcheck disable=SC2086
      "$wsntrack" watch "$PWD/plain-dir" $bad >out.txt 2>err.txt; rc=$?
      [ "$rc" -eq 2 ] || fail "watch $bad exited $rc, expected 2"
      # The option, not the non-run directory, must be what is refused.
      grep -q -- "${bad%% *}" err.txt && ! grep -q "not a wsntrack run directory" err.txt \
        || { cat err.txt >&2; fail "watch $bad: message does not name ${bad%% *}"; }
    done
    # The example refuses to start without the run's configuration (never Cyclone's default).
    env -u CYCLONEDDS_URI "$example" 5 abc >out.txt 2>err.txt; rc=$?
    [ "$rc" -eq 2 ] || fail "watch_tracks without CYCLONEDDS_URI exited $rc, expected 2"
    # --tick-interval is checked like the other run options.
    for bad in "--tick-interval -1" "--tick-interval nan" "--tick-interval 70"; do
      # shellcheck disable=SC2086
      "$wsntrack" run "$scenario" --quiet --no-plot --out "$PWD/never" $bad >out.txt 2>err.txt; rc=$?
      [ "$rc" -eq 2 ] || fail "run $bad exited $rc, expected 2"
      grep -q -- "--tick-interval" err.txt || { cat err.txt >&2; fail "run $bad: message does not name --tick-interval"; }
    done
    no_leftovers ;;

  dead_run)
    # A run that has finished, and one whose launcher was killed: nothing to watch. The watch
    # waits --timeout for a new run to start there, then exits 1 and says why.
    timeout 120 "$wsntrack" run "$scenario" --ticks 5 --quiet --no-plot --out "$PWD/finished" >/dev/null 2>finished.err \
      || { cat finished.err >&2; fail "short run"; }
    start=$(date +%s)
    "$wsntrack" watch "$PWD/finished" --timeout 2 >out.txt 2>err.txt & watcher=$!; started_pids+=("$watcher")
    wait_bounded "$watcher" 20 "wsntrack watch"
    [ "$rc" -eq 1 ] || { cat err.txt >&2; fail "watch on a finished run exited $rc, expected 1"; }
    grep -q "no run started in .* within 2 s: .*it finished" err.txt || { cat err.txt >&2; fail "unclear message for a finished run"; }
    [ $(( $(date +%s) - start )) -le 10 ] || fail "watch on a finished run took longer than its timeout allows"

    "$wsntrack" run "$scenario" --ticks 5000 --tick-interval 0.01 --quiet --no-plot --out "$PWD/killed" \
      >/dev/null 2>killed.err & launcher=$!; started_pids+=("$launcher")
    wait_for_run_json "$PWD/killed"
    sleep 2; kill -9 "$launcher"; wait "$launcher" 2>/dev/null
    "$wsntrack" watch "$PWD/killed" --timeout 2 >out.txt 2>err.txt & watcher=$!; started_pids+=("$watcher")
    wait_bounded "$watcher" 20 "wsntrack watch"
    [ "$rc" -eq 1 ] || { cat err.txt >&2; fail "watch on a killed run exited $rc, expected 1"; }
    grep -q "launcher (pid $launcher) exited before the run finished" err.txt || { cat err.txt >&2; fail "unclear message for a killed run"; }

    # A secured run whose credentials are gone while run.json still says running (as once its
    # launcher removed them): the watch says so instead of calling every viewer slot taken.
    "$wsntrack" run "$scenario" --ticks 300 --tick-interval 0.02 --quiet --no-plot --out "$PWD/nocreds" \
      >/dev/null 2>nocreds.err & launcher=$!; started_pids+=("$launcher")
    for _ in $(seq 1 300); do [ -f "$PWD/nocreds/logs/aggregator-0.log" ] && break; sleep 0.1; done
    sleep 1; rm -rf "$PWD/nocreds/credentials"
    "$wsntrack" watch "$PWD/nocreds" --timeout 5 >out.txt 2>err.txt & watcher=$!; started_pids+=("$watcher")
    wait_bounded "$watcher" 20 "wsntrack watch"
    [ "$rc" -eq 1 ] || { cat err.txt >&2; fail "watch on a run without its credentials exited $rc, expected 1"; }
    grep -q "credentials is gone: the run has ended" err.txt || { cat err.txt >&2; fail "unclear message for a run without credentials"; }
    wait_bounded "$launcher" 60 "the run without credentials"
    [ "$rc" -eq 0 ] || { cat nocreds.err >&2; fail "the run whose credentials were removed mid-run exited $rc"; }

    # The example on a run nobody serves: it gives up after its timeout.
    domain=$(json_value "$PWD/killed" domain); run_id=$(json_value "$PWD/killed" run_id)
    CYCLONEDDS_URI="file://$PWD/killed/cyclonedds.xml" WSN_PARTICIPANT_INDEX=$(json_value "$PWD/killed" participants) \
      "$example" "$domain" "$run_id" 2 >out.txt 2>err.txt & viewer=$!; started_pids+=("$viewer")
    wait_bounded "$viewer" 20 "watch_tracks"
    [ "$rc" -eq 1 ] || { cat err.txt >&2; fail "watch_tracks on a dead run exited $rc, expected 1"; }
    grep -q "nothing from run" err.txt || { cat err.txt >&2; fail "unclear message from watch_tracks on a dead run"; }
    no_leftovers ;;

  *) fail "unknown case $case_name" ;;
esac
echo "ok: $case_name"
