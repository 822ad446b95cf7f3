#!/usr/bin/env bash
# Runs every libFuzzer target of a WSN_FUZZ build for a fixed number of inputs from its seed corpus
# (fuzz/corpus/TARGET), seed 1, and fails on any crash, hang, out-of-memory or sanitizer report
# (docs/FUZZING.md). The inputs it finds go to a scratch corpus, never into the repository's.
#
#   fuzz/run_fuzzers.sh BUILD_DIR [--runs N]            every target; N inputs each instead of its own count
#   fuzz/run_fuzzers.sh BUILD_DIR --replay TARGET FILE...  runs TARGET on crash files (no fuzzing)
#
# A failing target's input lands in BUILD_DIR/fuzz-artifacts/TARGET-crash-... (or -timeout-, -oom-),
# which --replay runs again; a fixed crash becomes a regression test (docs/FUZZING.md).
set -uo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
usage() { sed -n '5,9p' "$0" | sed 's/^# \{0,1\}//'; }
[ $# -ge 1 ] || { usage >&2; exit 2; }
build="$(cd "$1" && pwd)" || exit 2
shift

# TARGET RUNS MAX_LEN: the inputs per target keep the whole CI stage (.ci/run, "fuzzers") within its
# budget on two cores (scenario: 25,000 inputs in about 55 s, the yaml-cpp hang of docs/FUZZING.md
# was at 2,200; samples: 1,000,000 in about 28 s); MAX_LEN bounds an input a little above the largest seed (scenarios of a few
# kB, samples of a few hundred bytes), so that libFuzzer spends its inputs on content, not length.
targets=("scenario 25000 16384" "samples 1000000 4096")
# Each input gets 10 s (a shipped scenario loads in milliseconds under ASan) and the process 2 GiB:
# beyond either, a tiny input has made the code hang or allocate without bound.
options=(-seed=1 -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=2048 -print_final_stats=1)
export ASAN_OPTIONS="${ASAN_OPTIONS:-abort_on_error=1:detect_leaks=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"

binary() { echo "$build/bin/wsn_fuzz_$1"; }
extra_options() {  # the target's dictionary, when it has one
  [ -f "$here/$1.dict" ] && echo "-dict=$here/$1.dict"
}

if [ "${1:-}" = "--replay" ]; then
  [ $# -ge 3 ] || { usage >&2; exit 2; }
  target="$2"; shift 2
  exec "$(binary "$target")" $(extra_options "$target") -runs=1 "$@"
fi
runs_override=""
if [ "${1:-}" = "--runs" ]; then
  runs_override="${2:?--runs needs a number}"
  shift 2
fi
[ $# -eq 0 ] || { usage >&2; exit 2; }

artifacts="$build/fuzz-artifacts"
mkdir -p "$artifacts"
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
failed=0
printf '%-10s %8s %8s %6s  %s\n' target inputs seconds seed result
for entry in "${targets[@]}"; do
  read -r name runs max_len <<<"$entry"
  [ -n "$runs_override" ] && runs="$runs_override"
  bin="$(binary "$name")"
  log="$artifacts/$name.log"
  if [ ! -x "$bin" ]; then
    printf '%-10s %8s %8s %6s  %s\n' "$name" - - 1 "FAILED: $bin not built (cmake --build BUILD_DIR --target wsn_fuzzers)"
    failed=1
    continue
  fi
  mkdir -p "$scratch/$name"
  start=$SECONDS
  "$bin" "${options[@]}" $(extra_options "$name") -runs="$runs" -max_len="$max_len" \
         -artifact_prefix="$artifacts/$name-" "$scratch/$name" "$here/corpus/$name" >"$log" 2>&1
  rc=$?
  done_runs="$(sed -n 's/^Done \([0-9]*\) runs in .*/\1/p' "$log" | tail -1)"
  # libFuzzer exits non-zero on a crash, a timeout or running out of memory; a sanitizer report
  # always ends the process (-fno-sanitize-recover, halt_on_error), so either says it. Both checked.
  if [ "$rc" -eq 0 ] && [ -n "$done_runs" ] && ! grep -qE '^(==[0-9]+==ERROR|SUMMARY: )|runtime error:' "$log"; then
    result="ok: 0 crashes, 0 hangs, 0 sanitizer reports ($(sed -n 's/^stat::new_units_added: *//p' "$log") new inputs)"
  else
    result="FAILED (exit $rc): $(grep -m1 -E 'ERROR|runtime error|Test unit written' "$log" || echo "see the log") -- log: $log"
    failed=1
  fi
  printf '%-10s %8s %8d %6s  %s\n' "$name" "${done_runs:-?}" $((SECONDS - start)) 1 "$result"
done
exit "$failed"
