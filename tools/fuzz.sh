#!/usr/bin/env bash
# Runs a libFuzzer target of streyes (fuzz/):
#   rib       the RIB parser, and what a parsed scene goes through (fuzz/rib_fuzz.cpp)
#   sl        the Shading Language compiler, source text in (fuzz/sl_fuzz.cpp)
#   vm        shaders compiled and run on a small grid by the interpreter (fuzz/vm_fuzz.cpp)
#   sequence  frame files and FrameBegin blocks read as one shot, then rendered (fuzz/sequence_fuzz.cpp)
#
#   tools/fuzz.sh                      build the fuzzers (cmake --preset fuzz, clang) and run rib 10 minutes
#   tools/fuzz.sh --target vm --seconds 3600 --jobs 2
#   tools/fuzz.sh --binary build-asan/streyes_fuzz_rib --seconds 10 --seed 1 --fresh   (what ctest runs)
#
# Seeds (read only): rib: scenes/, scenes/hard/, fuzz/seeds/, fuzz/regressions/; sl and vm:
# shaders/, fuzz/seeds-sl/, fuzz/regressions-sl/ (vm: and fuzz/regressions-vm/); sequence:
# fuzz/seeds-sequence/, fuzz/regressions-sequence/. Inputs that reach new code go to WORK/corpus
# (default build-fuzz/work for rib, build-fuzz/work-TARGET for the others), crashes to WORK/ as
# crash-*, leak-*, timeout-*. A crash stops the run with a non-zero exit: add the input to the
# target's regressions folder with the fix (tests/core/fuzz_regression_test.cpp replays every file
# there). --fresh starts from the seeds alone (libFuzzer's time limit does not cut short its first
# pass over the corpus, which grows).
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
target=rib seconds=600 jobs=1 binary="" work="" seed="" fresh=0
while (($#)); do
  case "$1" in
    --target) target=$2; shift 2 ;;
    --seconds) seconds=$2; shift 2 ;;
    --jobs) jobs=$2; shift 2 ;;
    --binary) binary=$2; shift 2 ;;
    --work) work=$2; shift 2 ;;
    --seed) seed=$2; shift 2 ;;
    --fresh) fresh=1; shift ;;
    *) echo "usage: tools/fuzz.sh [--target rib|sl|vm|sequence] [--seconds N] [--jobs N] [--binary PATH] [--work DIR] [--seed N] [--fresh]" >&2; exit 2 ;;
  esac
done
case "$target" in
  rib) what="the RIB parser" dict=rib.dict max_len=8192
       seeds=("$ROOT/scenes" "$ROOT/scenes/hard" "$ROOT/fuzz/seeds" "$ROOT/fuzz/regressions") ;;
  sl) what="the Shading Language compiler" dict=sl.dict max_len=8192
      seeds=("$ROOT/shaders" "$ROOT/fuzz/seeds-sl" "$ROOT/fuzz/regressions-sl") ;;
  vm) what="the Shading Language interpreter" dict=sl.dict max_len=8192
      seeds=("$ROOT/shaders" "$ROOT/fuzz/seeds-sl" "$ROOT/fuzz/regressions-sl" "$ROOT/fuzz/regressions-vm") ;;
  sequence) what="the frame-sequence reader" dict=rib.dict max_len=16384
            seeds=("$ROOT/fuzz/seeds-sequence" "$ROOT/fuzz/regressions-sequence") ;;
  *) echo "tools/fuzz.sh: --target is rib, sl, vm or sequence, not '$target'" >&2; exit 2 ;;
esac
if [ -z "$binary" ]; then
  cd "$ROOT"
  [ -f build-fuzz/CMakeCache.txt ] || cmake --preset fuzz >/dev/null
  cmake --build --preset fuzz
  binary=$ROOT/build-fuzz/streyes_fuzz_$target
fi
if [ "$target" = rib ]; then work=${work:-$ROOT/build-fuzz/work}; else work=${work:-$ROOT/build-fuzz/work-$target}; fi
((fresh)) && rm -rf "$work"
mkdir -p "$work/corpus"
log=$work/fuzz.log
# The time limit catches hangs, not slowness: the fuzzer runs under the address and undefined
# sanitizers with coverage, about 25x slower than a release build. A Blobby filling a 640x480
# Format polygonizes at its cap of 256 cells (1.2 s of parsing in release) and took 31 s here.
args=(-dict="$ROOT/fuzz/$dict" -max_total_time="$seconds" -max_len="$max_len" -timeout=60 -rss_limit_mb=2048
      -print_final_stats=1 -artifact_prefix="$work/")
[ -n "$seed" ] && args+=(-seed="$seed")
if ((jobs > 1)); then args+=(-jobs="$jobs" -workers="$jobs"); fi
existing=()
for d in "${seeds[@]}"; do [ -d "$d" ] && existing+=("$d"); done
echo "== Fuzzing $what for $seconds s ($binary)"
status=0
ASAN_OPTIONS=detect_leaks=1:intercept_tls_get_addr=0 UBSAN_OPTIONS=print_stacktrace=1 \
  "$binary" "${args[@]}" "$work/corpus" "${existing[@]}" >"$log" 2>&1 || status=$?
if ((jobs > 1)); then cat "$work"/fuzz-*.log >>"$log" 2>/dev/null || true; fi
runs=$( (grep -h "stat::number_of_executed_units" "$log" || true) | awk '{s += $2} END {print s + 0}')
if ((status != 0)); then
  grep -E "ERROR|SUMMARY|runtime error|Test unit written|deadly signal" "$log" | head -20 >&2
  echo "== The fuzzer failed after $runs executions: see $log" >&2
  exit 1
fi
echo "== $runs executions without a crash (corpus: $(ls "$work/corpus" | wc -l) inputs in $work/corpus)"
