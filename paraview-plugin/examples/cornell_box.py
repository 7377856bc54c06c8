"""The Cornell box, lit by one point light, with the Global Illumination representation.

Runs in pvbatch and pvpython (writes the picture to the .png path given, if any) and in
the GUI (`paraview --script=...`, which keeps the scene open to explore):

  PYTHONPATH=build/python3-paraview/usr/lib/python3/dist-packages \\
    xvfb-run -a pvbatch paraview-plugin/examples/cornell_box.py out.png

The plugin is loaded from $LINKGI_PLUGIN, else from the build tree beside this file, else
taken as loaded by the GUI.
"""
import os
import sys

from paraview.simple import *  # noqa: F401,F403 (the pvpython way)

try:
    HERE = os.path.dirname(os.path.abspath(__file__))
except NameError:  # the GUI runs --script files without __file__
    HERE = os.getcwd()
PLUGIN = os.environ.get("LINKGI_PLUGIN", os.path.join(
    HERE, "..", "..", "build", "paraview-plugin", "lib", "paraview-5.11", "plugins", "LinkGI",
    "LinkGI.so"))
if os.path.exists(PLUGIN):
    # Also makes the plugin's proxies Python functions here (loading it twice is harmless).
    LoadPlugin(PLUGIN, remote=False, ns=globals())
else:
    # Loaded by the GUI already (--plugins=LinkGI or the Plugin Manager): add its functions.
    import paraview.simple
    paraview.simple._add_functions(globals())

box = GlobalIlluminationScene(registrationName="CornellBox", Scene="cornell")
view = GetActiveViewOrCreate("RenderView")
view.OrientationAxesVisibility = 0
view.UseLight = 0  # only the ceiling light below (the light kit's key light would be bounced too)

# A point light 10 cm below the ceiling, as the Light Inspector makes them (a cone angle of
# 90 degrees or more means no spot).
light = CreateLight()
light.Coords = "Scene"
light.Type = "Positional"
light.Position = [0.278, 0.4488, 0.2795]
light.ConeAngle = 90
light.Intensity = 0.85
light.DiffuseColor = [1.0, 0.706, 0.235]
view.AdditionalLights = [light]

display = Show(box, view)
display.Representation = "Global Illumination"
display.GlobalIlluminationBounces = 3
display.GlobalIlluminationDisplayMode = "Combined"  # or "Direct", "Indirect"
# ParaView's lights do not fall off with distance (as in Surface); this one is a lamp, 1/r^2.
# The Automatic look then shows the box as an exposed photograph.
display.GlobalIlluminationLightFalloff = "Inverse Square"

view.CameraPosition = [0.278, 0.274, -0.75]
view.CameraFocalPoint = [0.278, 0.274, 0.28]
view.CameraViewUp = [0, 1, 0]
view.CameraViewAngle = 40
SetActiveSource(box)
Render(view)

if len(sys.argv) > 1 and sys.argv[1].endswith(".png"):
    SaveScreenshot(sys.argv[1], view, ImageResolution=[600, 600])
