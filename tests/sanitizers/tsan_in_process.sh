#!/usr/bin/env bash
# The in-process cluster (every role a thread of one process) under ThreadSanitizer: it must run
# without a report and give byte-identical outputs to the uninstrumented build.
# Usage: tsan_in_process.sh TSAN_BIN_DIR PLAIN_BIN_DIR SOURCE_DIR WORK_DIR
set -uo pipefail
tsan_bin="$1"; plain_bin="$2"; src="$3"; work="$4"
rm -rf "$work"; mkdir -p "$work"
fail() { echo "FAIL: $*" >&2; exit 1; }
run() {  # run BIN OUT: the default scenario, 40 ticks, two node tiles, in-process
  timeout 600 "$1/wsntrack" run "$src/scenarios/oh_quadrants.yaml" --in-process --nodes 2 --seed 7 --ticks 40 \
    --quiet --no-plot --out "$2" >"$2.stdout" 2>"$2.stderr"
}
export TSAN_OPTIONS="suppressions=$src/tests/sanitizers/tsan.supp:halt_on_error=1:exitcode=66:second_deadlock_stack=1"
run "$tsan_bin" "$work/tsan" || { cat "$work/tsan.stderr" >&2; fail "the in-process cluster under TSan exited $?"; }
grep -q "ThreadSanitizer" "$work/tsan.stderr" && { cat "$work/tsan.stderr" >&2; fail "TSan reported"; }
unset TSAN_OPTIONS
run "$plain_bin" "$work/plain" || { cat "$work/plain.stderr" >&2; fail "the uninstrumented run failed"; }
for f in tracks.csv tracks_supernode.csv observations.csv truth.csv network.json metrics_per_tick.csv; do
  cmp -s "$work/tsan/$f" "$work/plain/$f" || fail "$f differs between the TSan and the plain build"
done
echo "ok: the in-process cluster ran clean under TSan, outputs identical to the plain build"
