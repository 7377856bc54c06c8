"""pvbatch: the Global Illumination representation exported as ParaView shows it.

The Cornell box lit by a Light Inspector point light (inverse-square falloff, the lamp
look), drawn by the Global Illumination representation, is exported by the plugin's
LinkGIExport macro (run as the GUI's Macros menu runs it): the web page, opened in headless
Chromium at the view's size, shows what ParaView's screenshot shows (mean CIEDE2000 over
the covered pixels <= 2: the view's shadows are per pixel, the page's per vertex), with no
request leaving it; the glTF file holds the same triangles and colours.
"""
import os
import subprocess
import sys

from paraview.simple import *  # noqa: F401,F403 (the pvbatch idiom)

import linkgi_paraview_testing as t

arguments = t.parse_arguments()
t.load_plugin(arguments.plugin, globals())
out = os.path.join(arguments.output_dir, "Export")
os.makedirs(out, exist_ok=True)

view = CreateView("RenderView")
view.ViewSize = [480, 320]
view.OrientationAxesVisibility = 0
view.UseLight = 0
view.Background = [0.32, 0.34, 0.43]
light = CreateLight()
light.Coords, light.Type = "Scene", "Positional"
light.Position = [0.278, 0.4488, 0.2795]
light.ConeAngle = 180
light.Intensity = 0.85
view.AdditionalLights = [light]
box = GlobalIlluminationScene(Scene="cornell")
display = Show(box, view)
display.Representation = "Global Illumination"
display.GlobalIlluminationLightFalloff = "Inverse Square"
view.CameraPosition = [0.278, 0.274, -0.8]
view.CameraFocalPoint = [0.278, 0.274, 0.28]
view.CameraViewUp = [0, 1, 0]
SetActiveView(view)
SetActiveSource(box)
Render(view)
screenshot = os.path.join(out, "paraview.png")
SaveScreenshot(screenshot, view, ImageResolution=list(view.ViewSize), TransparentBackground=0)

# The macro, as the Macros menu runs it.
os.environ["LINKGI_EXPORT_DIR"] = out
macro = os.path.join(os.path.dirname(arguments.plugin), "..", "..", "..", "..", "share",
                     "paraview-5.11", "Macros", "LinkGIExport.py")
t.check(os.path.exists(macro), "the macro is in the build's share/paraview-5.11/Macros")
before = set(os.listdir(out))  # earlier runs' files stay
with open(macro) as f:
    exec(compile(f.read(), macro, "exec"), {"__name__": "__main__"})
written = sorted(set(os.listdir(out)) - before)
pages = [f for f in written if f.endswith(".html")]
glbs = [f for f in written if f.endswith(".glb")]
t.check(len(pages) == 1 and len(glbs) == 1, "the macro wrote a page and a glTF file: %s" % written)

import linkgi  # noqa: E402 (on sys.path since the macro ran)
import linkgi_export_testing as testing  # noqa: E402

scene = linkgi.bake(view)
t.check(len(scene.parts) == 1 and not scene.left_out, "one lit surface, nothing left out")
shot = os.path.join(out, "page.png")
requests = testing.open_in_chromium(os.path.join(out, pages[0]), "combined", shot)
t.check(not requests, "the page makes no request (%s)" % requests)
page = testing.read_png(shot)
shown = testing.read_png(screenshot)
keep = testing.panels_mask(page.shape, scene.legend is not None)
background = tuple(int(round(255 * c)) for c in scene.background)
difference, covered = testing.mean_difference(
    testing.np.where(keep[..., None], page, background).astype("uint8"),
    testing.np.where(keep[..., None], shown, background).astype("uint8"), background)
print("page against ParaView: mean CIEDE2000 %.2f over %d pixels" % (difference, covered))
t.check(covered > 0.2 * keep.sum(), "the page shows the box (%d pixels)" % covered)
t.check(difference <= 2.0, "the page shows what ParaView shows (mean CIEDE2000 %.2f)" % difference)
size = os.path.getsize(os.path.join(out, glbs[0]))
t.check(size > 12 * 3 * scene.points, "the glTF file holds the mesh (%d bytes)" % size)
