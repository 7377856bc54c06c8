"""What linkgi.export_html shares, beside what VTK draws: the README's five-minute scene (a
sphere on a plane under a lamp) drawn by vtkGlobalIlluminationMapper (left: shadows per
pixel, from shadow maps) and its exported web page in headless Chromium (right: the baked
per-vertex colours, shadows as sharp as the mesh, with the page's light-term toggle).

Usage (from the repository root, after building build/):
  PYTHONPATH=build/lib/python3.11/dist-packages Testing/run_with_xvfb.sh \\
    /usr/bin/python3 Documentation/export-images.py Documentation/export-page.png
"""
import os
import runpy
import sys
import tempfile

import numpy as np

TOP = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(TOP, "Testing", "Python"))

import linkgi  # noqa: E402
import linkgi_export_testing as testing  # noqa: E402 (Chromium as the tests drive it)


def main(path):
    with tempfile.TemporaryDirectory() as folder:
        sys.argv = ["five_minutes.py", os.path.join(folder, "vtk.png")]
        scene = runpy.run_path(os.path.join(TOP, "Examples", "Python", "five_minutes.py"))
        window = scene["window"]
        window.SetSize(*testing.SIZE)
        mapper = testing.grab(window)
        page = os.path.join(folder, "scene.html")
        linkgi.export_html(window, page)
        shot = os.path.join(folder, "page.png")
        testing.open_in_chromium(page, "combined", shot)
        gap = np.full((mapper.shape[0], 8, 3), 255, dtype=np.uint8)
        testing.write_png(np.hstack([mapper, gap, testing.read_png(shot)]), path)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "export-page.png")
