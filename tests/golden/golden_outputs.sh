#!/usr/bin/env bash
# Golden outputs: every shipped scenario, seed 1, with every tracker engine and aggregator
# association that accepts it, run in-process; the sha256 of each output file is compared with
# tests/golden/outputs.sha256 (recorded before a refactor that must not change behaviour).
#
#   golden_outputs.sh BIN_DIR SOURCE_DIR WORK_DIR check     compare with the recorded sums
#   golden_outputs.sh BIN_DIR SOURCE_DIR WORK_DIR record    rewrite the recorded sums
#
# CSV and YAML files are compared byte for byte. JSON files are compared by content: parsed,
# without "timing" and "provenance" (they describe the run, not its results), in the file's own
# key order (readers take keys by position too) and every number exactly (repr), so a change of
# layout or whitespace alone does not count but any change of a value or of the order does.
# A difference prints the work directory, whose run directories can be compared with a run of
# the previous commit.
set -euo pipefail
bin_dir=$1 source_dir=$2 work=$3 mode=$4
manifest=$source_dir/tests/golden/outputs.sha256
wsntrack=$bin_dir/wsntrack
rm -rf "$work" && mkdir -p "$work"
actual=$work/outputs.sha256
: >"$actual"
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
for scenario in "$source_dir"/scenarios/*.yaml; do
  name=$(basename "$scenario" .yaml)
  for engine in mcmcda gnn rulebased; do
    for association in mcmcda gated; do
      case_name=$name.$engine.$association
      # A pairing the scenario check rejects is not a case (validate says so, with a reason).
      if ! "$wsntrack" validate "$scenario" --set tracker.engine=$engine \
           --set aggregator.association=$association >/dev/null 2>&1; then
        echo "$case_name: rejected by validate, not a case"
        continue
      fi
      out=$work/$case_name
      "$wsntrack" run "$scenario" --seed 1 --in-process --quiet --no-plot --out "$out" \
        --set tracker.engine=$engine --set aggregator.association=$association >"$out.log" 2>&1 ||
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
cases=$(cut -d' ' -f3 "$actual" | cut -d/ -f1 | sort -u | wc -l)
if [[ $mode == record ]]; then
  cp "$actual" "$manifest"
  echo "recorded $(wc -l <"$actual") files of $cases cases in $manifest"
  exit 0
fi
if diff <(sort -k2 "$manifest") <(sort -k2 "$actual") >"$work/diff"; then
  echo "OK: $(wc -l <"$actual") files of $cases cases byte-identical to the recorded outputs"
  exit 0
fi
echo "FAIL: outputs differ from $manifest (< recorded, > now):"
cat "$work/diff"
echo "run directories: $work"
exit 1
