#!/usr/bin/env bash
# Installs what is missing, builds Release, and runs the whole test suite through ctest.
#   tools/test.sh           the release build (build/)
#   tools/test.sh --asan    the same suite under address and undefined-behaviour sanitizers
#                           (build-asan/, clang), with a brief libFuzzer run of the RIB parser
STREYES_SETUP_TESTS=1 source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
# The farm tests run on a one-node Slurm cluster that ctest's fixtures start (farm.cluster_start)
# and stop (farm.cluster_stop, pass or fail); should ctest itself be killed, this stops it too.
stop_cluster() {
  for dir in "$ROOT/build/slurm-local" "$ROOT/build-asan/slurm-local"; do
    [ -f "$dir/slurm.conf" ] && "$ROOT/tools/slurm-local.sh" stop "$dir" >/dev/null 2>&1 || true
  done
}
trap stop_cluster EXIT
if [ "${1:-}" = "--asan" ]; then
  shift
  # A tree configured with another compiler (GCC, before the preset moved to clang) starts
  # afresh: changing the compiler in place makes CMake drop the preset's other settings.
  if [ -f build-asan/CMakeCache.txt ] && ! grep -q '^CMAKE_CXX_COMPILER:.*clang' build-asan/CMakeCache.txt; then
    rm -rf build-asan/CMakeCache.txt build-asan/CMakeFiles
  fi
  [ -f build-asan/build.ninja ] || cmake --preset asan >/dev/null  # not the cache: see setup.sh
  echo "== Building with sanitizers (build-asan/)"
  cmake --build --preset asan -j "$(nproc)"
  echo "== Testing with sanitizers"
  ctest --preset asan -j "$(nproc)" "$@"
  exit
fi
echo "== Testing"
ctest --preset release -j "$(nproc)" "$@"
