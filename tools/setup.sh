#!/usr/bin/env bash
# Shared set-up for tools/demo.sh and tools/test.sh: installs the Debian packages streyes needs
# (when missing), then configures and builds the Release preset into build/.
# Sourced, not run: it leaves ROOT set to the project folder.
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)

# Boost.Wave's CMake package asks for Boost's atomic, chrono and thread packages, which Debian's
# libboost-wave-dev does not depend on: without them a fresh machine stops at configuring.
PACKAGES=(cmake ninja-build g++ pkg-config
          libopenimageio-dev openimageio-tools libopenexr-dev libimath-dev libdeflate-dev zlib1g-dev libosd-dev libtbb-dev libhwy-dev libjemalloc-dev libboost-wave-dev libnanoflann-dev
          libboost-atomic-dev libboost-chrono-dev libboost-thread-dev
          nlohmann-json3-dev libcli11-dev
          libgtest-dev libbenchmark-dev python3 python3-openimageio python3-numpy
          gnuplot-nox clang libclang-rt-14-dev)
# Only the test suite needs these: Blender renders the add-on's tests (blender/, tests/blender/)
# with streyes and with Cycles, headless. About 90 packages on a fresh machine (90 MB of
# downloads, 300 MB on disk): tools/test.sh installs them, tools/demo.sh does not.
TEST_PACKAGES=(blender)
if [ "${STREYES_SETUP_TESTS:-0}" = 1 ]; then
  PACKAGES+=("${TEST_PACKAGES[@]}")
fi

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  if [ "$(id -u)" -ne 0 ]; then
    echo "streyes needs these Debian packages: ${missing[*]}" >&2
    echo "Install them as root, then run this script again:" >&2
    echo "  apt-get update && apt-get install -y ${missing[*]}" >&2
    exit 1
  fi
  echo "== Installing ${#missing[@]} Debian packages: ${missing[*]}"
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

cd "$ROOT"
# build.ninja, not CMakeCache.txt: a configure that failed (a package missing) leaves the cache
# behind, and the next run must configure again rather than stop at "loading build.ninja".
if [ ! -f build/build.ninja ]; then
  echo "== Configuring (release preset, build/)"
  cmake --preset release >/dev/null
fi
echo "== Building"
cmake --build --preset release -j "$(nproc)"
