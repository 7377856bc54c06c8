#!/usr/bin/env bash
# Command 2: set up, build, and run the whole test suite through one ctest run.
set -euo pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
"$top/scripts/setup.sh" --paraview-python
"$top/scripts/build.sh"
cd "$top/build"
ctest --output-on-failure -j "$(nproc)" --timeout 900
