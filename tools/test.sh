#!/usr/bin/env bash
# Installs what is missing, builds Release, and runs the whole test suite through ctest.
#   tools/test.sh           the release build (build/), with a brief libFuzzer run
#   tools/test.sh --asan    the same suite under address and undefined-behaviour sanitizers
#                           (build-asan/); the fuzzer is sanitized itself and is not run again
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
if [ "${1:-}" = "--asan" ]; then
  shift
  [ -f build-asan/CMakeCache.txt ] || cmake --preset asan >/dev/null
  echo "== Building with sanitizers (build-asan/)"
  cmake --build --preset asan -j "$(nproc)"
  echo "== Testing with sanitizers"
  exec ctest --preset asan -j "$(nproc)" "$@"
fi
echo "== Testing"
ctest --preset release -j "$(nproc)" "$@"
