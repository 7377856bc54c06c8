"""linkgi.export_html writes a page that shows what VTK shows, in a real browser, offline.

Debian's Chromium, headless, with a fresh profile, opens the exported page from disk at
the window's size. For each light term (the page's toggle, selected by the URL's #combined,
#direct, #indirect as its buttons do), its screenshot matches VTK drawing the same baked
colours unlit at the saved camera: mean CIEDE2000 <= 2 over the covered pixels (the
toggle's and the legend's panels left out). The terms differ from one another, so the
toggle switches them. Chromium's network log shows no request made by the page (a control
page with a remote image shows that such a request would be seen).

Usage: TestExportHtml.py [output directory for the pages and images]
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile

import numpy as np

import linkgi
import linkgi_export_testing as testing

CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")


def open_in_chromium(page, fragment, screenshot):
    """Screenshot of `page`#`fragment`, and the URLs of the requests the page made."""
    with tempfile.TemporaryDirectory() as profile:
        net_log = os.path.join(profile, "net.json")
        command = [
            CHROMIUM, "--headless=new", "--no-sandbox", "--disable-gpu", "--use-gl=swiftshader",
            "--enable-unsafe-swiftshader", f"--window-size={testing.SIZE[0]},{testing.SIZE[1]}",
            "--force-device-scale-factor=1", "--hide-scrollbars", f"--user-data-dir={profile}",
            "--no-first-run", "--disable-background-networking", "--disable-component-update",
            "--disable-sync", "--virtual-time-budget=15000", f"--log-net-log={net_log}",
            f"--screenshot={screenshot}", f"file://{os.path.abspath(page)}#{fragment}"]
        subprocess.run(command, check=True, timeout=120, stdout=subprocess.DEVNULL,
                       stderr=subprocess.DEVNULL)
        with open(net_log) as f:
            log = json.load(f)
    start = log["constants"]["logEventTypes"]["URL_REQUEST_START_JOB"]
    # Chromium's own requests (updates, accounts) have no origin; the page's have its own.
    requests = [e.get("params", {}) for e in log["events"] if e["type"] == start]
    return [r["url"] for r in requests if "url" in r and r.get("initiator") != "not an origin"
            and not r["url"].startswith(("file:", "data:", "blob:"))]


def panels_mask(shape, legend):
    """The pixels outside the page's panels (the toggle top left, the legend bottom right)."""
    keep = np.ones(shape[:2], dtype=bool)
    keep[:48, :260] = False
    if legend:
        keep[-80:, -250:] = False
    return keep


out = testing.output_dir(sys.argv)
assert CHROMIUM, "Chromium is missing (scripts/setup.sh installs it)"

# The detector sees a page's request.
control = os.path.join(out, "control.html")
with open(control, "w") as f:
    f.write('<html><body><img src="https://linkgi.invalid/remote.png"></body></html>')
seen = open_in_chromium(control, "", os.path.join(out, "control.png"))
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
        requests = open_in_chromium(page, mode, path)
        assert not requests, f"{name}: the page made requests: {requests}"
        browser = testing.read_png(path)
        vtk = testing.grab(testing.baked_window(scene, mode))
        testing.write_png(vtk, os.path.join(out, f"{name}-{mode}-vtk.png"))
        keep = panels_mask(browser.shape, scene.legend is not None)
        difference, covered = testing.mean_difference(
            np.where(keep[..., None], browser, background).astype(np.uint8),
            np.where(keep[..., None], vtk, background).astype(np.uint8), background)
        print(f"{name} {mode}: mean CIEDE2000 {difference:.2f} over {covered} pixels")
        assert covered > 0.3 * keep.sum(), f"{name} {mode}: the page shows nothing ({covered})"
        assert difference <= 2.0, f"{name} {mode}: the page differs from VTK: {difference:.2f}"
        shots[mode] = np.where(keep[..., None], browser, background).astype(np.uint8)
    for other in ("direct", "indirect"):
        apart, _ = testing.mean_difference(shots["combined"], shots[other], background)
        assert apart > 0.3, f"{name}: the toggle's {other} looks like combined ({apart:.2f})"
    if name == "colour-map":
        with open(page, encoding="utf-8") as f:
            assert 'id="linkgi-legend"' in f.read(), "the colour map has no legend"
print("ok")
