#!/usr/bin/env bash
# Installs what is missing, builds Release, and runs the whole test suite through ctest.
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
echo "== Testing"
ctest --preset release -j "$(nproc)" "$@"
