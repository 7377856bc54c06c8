#!/usr/bin/env bash
# Command 1: set up, build, and render the built-in demo scene to a PNG.
# Usage: scripts/demo.sh [output.png]
set -euo pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
"$top/scripts/setup.sh"
"$top/scripts/build.sh"
out=$(realpath -m "${1:-$top/build/linkgi-demo.png}")
# Offscreen rendering through Mesa under a virtual X server.
xvfb-run -a -s "-screen 0 1280x1024x24" "$top/build/bin/linkgi-demo" "$out"
