"""linkgi.export_html writes a page that shows what VTK shows, in a real browser, offline.

Debian's Chromium, headless, with a fresh profile, opens the exported page from disk at
the window's size. For each light term (the page's toggle, selected by the URL's #combined,
#direct, #indirect as its buttons do), its screenshot matches VTK drawing the same baked
colours unlit at the saved camera: mean CIEDE2000 <= 2 over the covered pixels (the
toggle's and the legend's panels left out). Under the lamp the terms differ from one
another, so the toggle switches them. Chromium's network log shows no request made by the
page (a control page with a remote image shows that such a request would be seen). A scene
beyond what a browser holds in one string is refused with an error that says what to do.

Usage: TestExportHtml.py [output directory for the pages and images]
"""
import os
import sys

import numpy as np

import linkgi
import linkgi_export_testing as testing

out = testing.output_dir(sys.argv)

# The detector sees a page's request.
control = os.path.join(out, "control.html")
with open(control, "w") as f:
    f.write('<html><body><img src="https://linkgi.invalid/remote.png"></body></html>')
seen = testing.open_in_chromium(control, "", os.path.join(out, "control.png"))
assert any("linkgi.invalid" in url for url in seen), f"the network log missed a request: {seen}"

for name, window in (("lamp", testing.lamp_scene()), ("colour-map", testing.colour_map_scene())):
    scene = linkgi.bake(window)
    page = os.path.join(out, f"{name}.html")
    report = linkgi.export_html(window, page)
    print(name, report)
    assert report["bytes"] == os.path.getsize(page)
    assert report["triangles"] == scene.triangles and report["points"] == scene.points
    background = tuple(int(round(255 * c)) for c in scene.background)
    shots = {}
    for mode in ("combined", "direct", "indirect"):
        path = os.path.join(out, f"{name}-{mode}-browser.png")
        requests = testing.open_in_chromium(page, mode, path)
        assert not requests, f"{name}: the page made requests: {requests}"
        browser = testing.read_png(path)
        vtk = testing.grab(testing.baked_window(scene, mode))
        testing.write_png(vtk, os.path.join(out, f"{name}-{mode}-vtk.png"))
        keep = testing.panels_mask(browser.shape, scene.legend is not None)
        difference, covered = testing.mean_difference(
            np.where(keep[..., None], browser, background).astype(np.uint8),
            np.where(keep[..., None], vtk, background).astype(np.uint8), background)
        print(f"{name} {mode}: mean CIEDE2000 {difference:.2f} over {covered} pixels")
        assert covered > 0.3 * keep.sum(), f"{name} {mode}: the page shows nothing ({covered})"
        assert difference <= 2.0, f"{name} {mode}: the page differs from VTK: {difference:.2f}"
        shots[mode] = np.where(keep[..., None], browser, background).astype(np.uint8)
    # Under the lamp the terms look apart (under the directional light little bounces).
    for other in ("direct", "indirect") if name == "lamp" else ():
        apart, _ = testing.mean_difference(shots["combined"], shots[other], background)
        assert apart > 1.0, f"{name}: the toggle's {other} looks like combined ({apart:.2f})"
    if name == "colour-map":
        with open(page, encoding="utf-8") as f:
            assert 'id="linkgi-legend"' in f.read(), "the colour map has no legend"
# Past what a browser can parse, a clear error and no file.
from linkgi import _vtkjs  # noqa: E402
limit = _vtkjs.BROWSER_STRING_LIMIT
_vtkjs.BROWSER_STRING_LIMIT = 1000
too_large = os.path.join(out, "too-large.html")
try:
    linkgi.export_html(testing.lamp_scene(), too_large)
    raise AssertionError("a scene beyond the browser's string limit was written")
except ValueError as error:
    assert "decimate" in str(error) and "export_glb" in str(error), error
    assert not os.path.exists(too_large)
finally:
    _vtkjs.BROWSER_STRING_LIMIT = limit
print("ok")
