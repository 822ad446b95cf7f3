#!/usr/bin/env bash
# Golden outputs: shipped scenarios, seed 1, with every registered tracker engine and aggregator
# association that accepts them, run in-process; the sha256 of each output file is compared with
# tests/golden/outputs.sha256 (recorded before a refactor that must not change behaviour).
#
#   golden_outputs.sh BIN_DIR SOURCE_DIR WORK_DIR check  [SCENARIO_NAME...]   compare with the recorded sums
#   golden_outputs.sh BIN_DIR SOURCE_DIR WORK_DIR record [SCENARIO_NAME...]   rewrite the recorded sums
#
# Without names, every scenarios/*.yaml but the scale_* benchmarks; with names (ctest runs one scenario per test, so -j
# spreads them), only those, and `record` replaces only their lines of the manifest.
#
# The engines and associations come from `wsntrack components --names`, not from this script, so
# a newly registered one is a case at once. A case is a scenario × engine × association that
# `wsntrack validate` accepts. `check` fails when a recorded case is not run (rejected, or its
# engine no longer registered), when a case runs that was never recorded (a new engine or scenario
# must be recorded on purpose), or when any file's sum differs.
#
# CSV and YAML files are compared byte for byte. JSON files are compared by content: parsed,
# without "timing" and "provenance" (they describe the run, not its results), in the file's own
# key order (readers take keys by position too) and every number exactly (repr), so a change of
# layout or whitespace alone does not count but any change of a value or of the order does.
# A difference prints the work directory, whose run directories can be compared with a run of
# the previous commit.
set -euo pipefail
[[ $# -ge 4 && ($4 == check || $4 == record) ]] || { sed -n '6,7p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }
bin_dir=$1 source_dir=$2 work=$3 mode=$4
shift 4
manifest=$source_dir/tests/golden/outputs.sha256
wsntrack=$bin_dir/wsntrack
if (($#)); then names=("$@"); else
  names=()
  # The scale_* benchmark scenarios are no golden cases (tests/golden/CMakeLists.txt says why).
  for scenario in "$source_dir"/scenarios/*.yaml; do
    name=$(basename "$scenario" .yaml)
    [[ $name == scale_* ]] || names+=("$name")
  done
fi
rm -rf "$work" && mkdir -p "$work"
actual=$work/outputs.sha256
: >"$actual"
mapfile -t engines < <("$wsntrack" components --names engines)
mapfile -t associations < <("$wsntrack" components --names associations)
((${#engines[@]} && ${#associations[@]})) || { echo "FAIL: wsntrack components --names lists no engine or association"; exit 1; }
files=(scenario.yaml truth.csv observations.csv tracks_supernode.csv tracks.csv tracks_settled.csv metrics_per_tick.csv network.json
       metrics.json)
normalise_json() {
  /usr/bin/python3 -c '
import json, sys
def norm(v):
    if isinstance(v, dict):
        return {k: norm(x) for k, x in v.items() if k not in ("timing", "provenance")}
    if isinstance(v, list):
        return [norm(x) for x in v]
    if isinstance(v, float):
        return repr(v)
    return v
print(json.dumps(norm(json.load(open(sys.argv[1]))), indent=1))' "$1"
}
for name in "${names[@]}"; do
  scenario=$source_dir/scenarios/$name.yaml
  [[ -f $scenario ]] || { echo "FAIL: no scenario $scenario"; exit 1; }
  for engine in "${engines[@]}"; do
    for association in "${associations[@]}"; do
      case_name=$name.$engine.$association
      # A pairing the scenario check rejects is not a case (validate says so, with a reason).
      if ! "$wsntrack" validate "$scenario" --set tracker.engine="$engine" \
           --set aggregator.association="$association" >"$work/$case_name.validate" 2>&1; then
        echo "$case_name: rejected by validate, not a case ($(tail -n 1 "$work/$case_name.validate"))"
        continue
      fi
      out=$work/$case_name
      "$wsntrack" run "$scenario" --seed 1 --in-process --quiet --no-plot --out "$out" \
        --set tracker.engine="$engine" --set aggregator.association="$association" >"$out.log" 2>&1 ||
        { echo "FAIL: $case_name did not run:"; cat "$out.log"; exit 1; }
      for f in "${files[@]}"; do
        src=$out/$f
        [[ -f $src ]] || { echo "FAIL: $case_name has no $f"; exit 1; }
        if [[ $f == *.json ]]; then
          normalise_json "$src" >"$src.normalised" || { echo "FAIL: $case_name/$f is not JSON"; exit 1; }
          src=$src.normalised
        fi
        echo "$(sha256sum <"$src" | cut -d' ' -f1)  $case_name/$f" >>"$actual"
      done
      echo "$case_name: ran"
    done
  done
done
# The manifest's lines of the scenarios this call covers: a case name is SCENARIO.ENGINE.ASSOCIATION
# (scenario file names have no dots).
recorded=$work/recorded.sha256
: >"$recorded"
for name in "${names[@]}"; do
  grep -F "  $name." "$manifest" >>"$recorded" || true
done
cases_in() { cut -d' ' -f3 "$1" | cut -d/ -f1 | sort -u; }
ran=$(cases_in "$actual" | wc -l)
if [[ $mode == record ]]; then
  others=$work/others.sha256
  grep -v -x -F -f "$recorded" "$manifest" >"$others" || true
  sort -k2 "$others" "$actual" >"$manifest"
  echo "recorded $(wc -l <"$actual") files of $ran cases of ${#names[@]} scenarios in $manifest"
  exit 0
fi
missing=$(comm -23 <(cases_in "$recorded") <(cases_in "$actual"))
unrecorded=$(comm -13 <(cases_in "$recorded") <(cases_in "$actual"))
status=0
if [[ -n $missing ]]; then
  echo "FAIL: recorded cases that did not run (rejected by validate, or engine/association no longer listed):"
  echo "$missing" | sed 's/^/  /'
  status=1
fi
if [[ -n $unrecorded ]]; then
  echo "FAIL: cases that ran but were never recorded (record them: $0 BIN SRC WORK record ${names[*]}):"
  echo "$unrecorded" | sed 's/^/  /'
  status=1
fi
if ! diff <(sort -k2 "$recorded") <(sort -k2 "$actual") >"$work/diff"; then
  echo "FAIL: outputs differ from $manifest (< recorded, > now):"
  cat "$work/diff"
  status=1
fi
if ((status)); then
  echo "run directories: $work"
  exit 1
fi
echo "OK: $(wc -l <"$actual") files of $ran cases (engines: ${engines[*]}; associations: ${associations[*]}) byte-identical to the recorded outputs"
