#!/usr/bin/env bash
# Installs what is missing, builds Release, and renders the demo scene to out/.
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
mkdir -p out
echo "== Rendering scenes/demo.rib"
build/streyes render scenes/demo.rib -o out/demo.####.exr --stats out/demo-stats.json "$@"
first=$(ls out/demo.*.exr | head -n 1)
last=$(ls out/demo.*.exr | tail -n 1)
echo "== Wrote $(ls out/demo.*.exr | wc -l) frames: $first ... $last"
echo "   statistics: out/demo-stats.json"
command -v iinfo >/dev/null && iinfo -v "$first" | grep -E "channel list|^ *$first" || true
