"""Surface beside Global Illumination on a scientific dataset: an isosurface of ParaView's
Wavelet coloured by elevation through the default colour map (Cool to Warm), over a plane,
under the view's default lights (the light kit) plus one directional light from the side
that throws the isosurface's shadow onto the plane in front of the camera.

Where light arrives directly and unblocked, the two views show the same colours (the
representation is calibrated to Surface); Global Illumination adds the shadows and the
light bounced between the isosurface and the plane.

  PYTHONPATH=build/python3-paraview/usr/lib/python3/dist-packages \\
    xvfb-run -a pvbatch paraview-plugin/examples/surface_vs_global_illumination.py out.png
"""
import os
import sys

from paraview.simple import *  # noqa: F401,F403 (the pvpython way)

HERE = os.path.dirname(os.path.abspath(__file__))
PLUGIN = os.environ.get("LINKGI_PLUGIN", os.path.join(
    HERE, "..", "..", "build", "paraview-plugin", "lib", "paraview-5.11", "plugins", "LinkGI",
    "LinkGI.so"))
LoadPlugin(PLUGIN, remote=False, ns=globals())

wavelet = Wavelet(WholeExtent=[-40, 40, -40, 40, -40, 40])
contour = Contour(Input=wavelet, ContourBy=["POINTS", "RTData"], Isosurfaces=[160.0])
elevation = Elevation(Input=contour, LowPoint=[0, 0, -40], HighPoint=[0, 0, 40])
floor = Plane(Origin=[-90, -90, -45], Point1=[90, -90, -45], Point2=[-90, 90, -45],
              XResolution=90, YResolution=90)
# The plane takes the colour map's middle, a light grey. Appended into one surface, so that
# the isosurface shadows the plane and light bounces between them.
floor = Calculator(Input=floor, ResultArrayName="Elevation", Function="0.5", ResultArrayType="Float")
scene = AppendGeometry(Input=[elevation, floor])

side = CreateLight()  # directional, from the left and above, in scene coordinates
side.Coords = "Scene"
side.Type = "Directional"
side.Position = [-1.0, 0.4, 1.0]
side.FocalPoint = [0, 0, 0]
side.Intensity = 0.5

layout = CreateLayout("Surface vs Global Illumination")
layout.SplitHorizontal(0, 0.5)
views = []
for i, representation in enumerate(("Surface", "Global Illumination")):
    view = CreateView("RenderView")
    layout.AssignView(1 + i, view)
    view.OrientationAxesVisibility = 0
    view.AdditionalLights = [side]
    display = Show(scene, view)
    ColorBy(display, ("POINTS", "Elevation"))
    display.Representation = representation
    if representation == "Global Illumination":
        display.GlobalIlluminationRays = 144
    Render(view)  # the first render resets the camera
    view.CameraPosition = [40, -230, 150]
    view.CameraFocalPoint = [0, 0, -15]
    view.CameraViewUp = [0, 0, 1]
    view.CameraViewAngle = 30
    views.append(view)
for view in views:
    Render(view)

if len(sys.argv) > 1 and sys.argv[1].endswith(".png"):
    SaveScreenshot(sys.argv[1], layout, ImageResolution=[1200, 450], TransparentBackground=0)
