#!/usr/bin/env bash
# Makes Documentation/paraview-gui.png: the ParaView GUI under Xvfb with the plugin loaded
# and examples/cornell_box.py shown with the Global Illumination representation.
# Needs xdotool (to size the window and its panels) and libqt5svg5 (the GUI's icons);
# the tests need neither, so scripts/setup.sh does not install them.
# Usage: paraview-plugin/examples/gui_screenshot.sh [output.png]   (after scripts/build.sh)
set -euo pipefail
top=$(cd "$(dirname "$0")/../.." && pwd)
out=$(realpath -m "${1:-$top/Documentation/paraview-gui.png}")
plugin_dir="$top/build/paraview-plugin/lib/paraview-5.11/plugins/LinkGI"
export PYTHONPATH="$top/build/python3-paraview/usr/lib/python3/dist-packages"
export DISPLAY=:87 LINKGI_PLUGIN="$plugin_dir/LinkGI.so"

Xvfb "$DISPLAY" -screen 0 1600x1000x24 -noreset >/dev/null 2>&1 &
xvfb=$!
paraview --dr --plugin-search-paths="$plugin_dir" --plugins=LinkGI \
  --script="$top/paraview-plugin/examples/cornell_box.py" >/dev/null 2>&1 &
gui=$!
trap 'kill $gui $xvfb 2>/dev/null || true' EXIT
sleep 15
for window in $(xdotool search --name "ParaView 5"); do
  xdotool windowmove "$window" 0 0 windowsize "$window" 1600 1000
done
sleep 3
# Widen the panels, then give the Properties panel the height of the Pipeline Browser.
xdotool mousemove 295 700 mousedown 1 sleep 0.3 mousemove 350 700 sleep 0.3 \
  mousemove 560 700 sleep 0.3 mouseup 1
xdotool mousemove 120 437 mousedown 1 sleep 0.3 mousemove 120 300 sleep 0.3 \
  mousemove 120 240 sleep 0.3 mouseup 1
sleep 2
/usr/bin/python3 -c "
import sys
from PIL import ImageGrab
ImageGrab.grab(xdisplay='$DISPLAY').convert('RGB').save(sys.argv[1], optimize=True)" "$out"
echo "wrote $out"
