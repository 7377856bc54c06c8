"""pvbatch: the plugin's "Global Illumination" representation with the view's lights.

1. The Cornell box (the plugin's Global Illumination Scene source) lit by a point light
   of the Light Inspector's kind (CreateLight), light kit off: the screenshot must match
   the reviewed baseline, and the filter must have run once, with that one light, with
   progress reaching the session's progress handler (what the GUI's progress bar shows).
2. Moving the light: the indirect light changes, the light links and bounces are redone,
   the links are not rebuilt. Switching the display mode recomputes nothing.
3. A built-in source with the light kit on and no other light: the kit's key light is the
   one light bounced, and orbiting the camera (the key light follows it) relights without
   relinking.
"""
from paraview import servermanager
from paraview.simple import *  # noqa: F401,F403 (the pvpython way)

import linkgi_paraview_testing as t

arguments = t.parse_arguments()
t.load_plugin(arguments.plugin, globals())


def statistics(display):
    """What the representation's last update did (its information properties)."""
    proxy = display.SMProxy
    proxy.UpdatePropertyInformation()
    names = ("LinkBuilds", "LightLinkBuilds", "BounceRuns", "Updates", "Lights", "MeanIndirect")
    return {n: proxy.GetProperty("GlobalIllumination" + n).GetElement(0) for n in names}


progress = []
handler = servermanager.ActiveConnection.Session.GetProgressHandler()
handler.SetProgressInterval(0.01)
handler.AddObserver("ProgressEvent", lambda h, e: progress.append(h.GetLastProgress()))

# 1. Cornell box and a point light 10 cm below the ceiling.
view = CreateView("RenderView")
view.ViewSize = [400, 400]
view.OrientationAxesVisibility = 0
view.UseLight = 0
view.Background = [0.32, 0.34, 0.43]
light = CreateLight()
light.Coords = "Scene"
light.Type = "Positional"
light.Position = [0.278, 0.4488, 0.2795]
light.ConeAngle = 180
light.Intensity = 0.85
light.DiffuseColor = [1.0, 0.706, 0.235]
view.AdditionalLights = [light]

box = GlobalIlluminationScene(Scene="cornell")
display = Show(box, view)
display.Representation = "Global Illumination"
# This test counts the solver's runs of each update: without progressive stages, whose coarse
# solutions run on the same solver (TestGlobalIlluminationAsynchronous draws them).
display.GlobalIlluminationProgressive = 0
display.GlobalIlluminationRays = 256
display.GlobalIlluminationBounces = 3
display.GlobalIlluminationSmoothing = 1
# A lamp 10 cm under the ceiling: Inverse Square makes the Light Inspector's point light fall
# off as a lamp's, and the Automatic look then compresses its wide range (1/r^2) as a
# photograph.
display.GlobalIlluminationLightFalloff = "Inverse Square"
view.CameraPosition = [0.278, 0.274, -0.8]
view.CameraFocalPoint = [0.278, 0.274, 0.28]
view.CameraViewUp = [0, 1, 0]
view.CameraViewAngle = 40
Render(view)

first = statistics(display)
t.check(first["Lights"] == 1 and first["Updates"] == 1 and first["LinkBuilds"] == 1,
        "the first render ran the filter once with the one point light: %s" % first)
t.check(first["MeanIndirect"] > 0.0, "the walls receive indirect light")
t.check(len(progress) >= 3, "the update reported progress (%d events)" % len(progress))
t.compare_with_baseline(view, "ParaViewGlobalIlluminationRepresentation", arguments)

# 2. Move the light.
light.Position = [0.15, 0.4488, 0.15]
Render(view)
moved = statistics(display)
t.check(moved["LinkBuilds"] == 1, "moving the light rebuilt no links")
t.check(moved["LightLinkBuilds"] == 2 and moved["BounceRuns"] == 2 and moved["Updates"] == 2,
        "moving the light redid the light links and the bounces once: %s" % moved)
change = abs(moved["MeanIndirect"] - first["MeanIndirect"]) / first["MeanIndirect"]
t.check(change > 0.01, "moving the light changed the indirect light (by %.1f %%)" % (100 * change))
display.GlobalIlluminationDisplayMode = "Indirect"
Render(view)
t.check(statistics(display)["Updates"] == 2, "switching the display mode recomputed nothing")
display.GlobalIlluminationDisplayMode = "Combined"

# 3. The light kit's key light on a built-in source.
Hide(box, view)
sphere = Sphere(Center=[0, 0.8, 0], Radius=0.5, ThetaResolution=32, PhiResolution=32)
floor = Plane(Origin=[-2, 0, -2], Point1=[-2, 0, 2], Point2=[2, 0, -2], XResolution=20,
              YResolution=20)
scene = AppendGeometry(Input=[sphere, floor])
kit = Show(scene, view)
kit.Representation = "Global Illumination"
kit.GlobalIlluminationProgressive = 0
kit.GlobalIlluminationRays = 64
view.AdditionalLights = []
view.UseLight = 1
view.CameraPosition = [0, 3, 6]
view.CameraFocalPoint = [0, 0.5, 0]
Render(view)
lit = statistics(kit)
t.check(lit["Lights"] == 1 and lit["Updates"] == 1,
        "with only the light kit, its key light is the one light bounced: %s" % lit)
GetActiveCamera().Azimuth(40)
Render(view)
orbit = statistics(kit)
t.check(orbit["LinkBuilds"] == 1 and orbit["LightLinkBuilds"] == 2,
        "orbiting the camera moved the key light: relit, not relinked: %s" % orbit)
kit.GlobalIlluminationKeyLight = 0
Render(view)
t.check(statistics(kit)["Lights"] == 0, "Bounce Key Light off leaves no light to bounce")
