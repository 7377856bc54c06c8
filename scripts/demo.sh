#!/usr/bin/env bash
# Command 1: set up, build, and render the built-in demo scene to a PNG.
# Usage: scripts/demo.sh [output.png]
set -euo pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
"$top/scripts/setup.sh"
"$top/scripts/build.sh"
out=$(realpath -m "${1:-$top/build/linkgi-demo.png}")
# Offscreen rendering through Mesa under a virtual X server of its own.
"$top/Testing/run_with_xvfb.sh" "$top/build/bin/linkgi-demo" "$out"
