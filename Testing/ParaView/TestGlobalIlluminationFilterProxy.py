"""pvbatch: the plugin's Global Illumination filter proxy on a sphere over a plane.

Checks the output arrays against the radiometry of a point light (E = I cos / r^2, a
shadow under the sphere, bounced light under it), the LinkGI.* counters in field data
(moving a light must not rebuild the links), a ParaView light proxy given as an additional
light, that progress reaches the session's progress handler (what the GUI's progress
bar shows), and that the sphere and the plane as two blocks of a group are one scene: each
block gets the arrays of its points in the appended surface.
"""
import math

from paraview import servermanager
from paraview.simple import *  # noqa: F401,F403 (the pvpython way)

import linkgi_paraview_testing as t

arguments = t.parse_arguments()
t.load_plugin(arguments.plugin, globals())

sphere = Sphere(Center=[0, 0.8, 0], Radius=0.5, ThetaResolution=48, PhiResolution=48)
plane = Plane(Origin=[-2, 0, -2], Point1=[-2, 0, 2], Point2=[2, 0, -2],  # normal +y
              XResolution=40, YResolution=40)
scene = AppendGeometry(Input=[sphere, plane])
scene.UpdatePipeline()

progress = []
handler = servermanager.ActiveConnection.Session.GetProgressHandler()
handler.SetProgressInterval(0.01)
handler.AddObserver("ProgressEvent",
                    lambda h, e: progress.append((h.GetLastProgressText(), h.GetLastProgress())))

gi = GlobalIllumination(Input=scene)
t.check(gi.LightType == "Directional" and gi.RaysPerVertex == "256" and gi.NumberOfBounces == 3,
        "defaults: directional light, 256 rays per vertex, 3 bounces")
gi.LightType = "Point"
gi.LightPosition = [0, 3, 0]
gi.LightIntensity = 9.0
gi.UpdatePipeline()
out = t.fetch(gi)

for name in ("DirectIrradiance", "IndirectIrradiance", "Radiance"):
    array = out.GetPointData().GetArray(name)
    t.check(array is not None and array.GetNumberOfComponents() == 3
            and array.GetNumberOfTuples() == out.GetNumberOfPoints(),
            "float RGB point array %s" % name)
    t.check(min(array.GetRange(c)[0] for c in range(3)) >= 0.0, "%s is not negative" % name)
t.check(any(p[0] != "" for p in progress) and len(progress) >= 3,
        "progress reached the session's progress handler (%d events)" % len(progress))

top = t.nearest_point(out, [0, 1.3, 0])
bottom = t.nearest_point(out, [0, 0.3, 0])
under = t.nearest_point(out, [0, 0, 0])
open_floor = t.nearest_point(out, [1.5, 0, 0])
expected_top = 9.0 / 1.7 ** 2
direct_top = t.point_rgb(out, "DirectIrradiance", top)[0]
t.check(abs(direct_top - expected_top) < 0.05 * expected_top,
        "top of the sphere: E = I / r^2 = %.3f (got %.3f)" % (expected_top, direct_top))
expected_floor = 9.0 * 3.0 / math.sqrt(11.25) / 11.25
direct_floor = t.point_rgb(out, "DirectIrradiance", open_floor)[0]
t.check(abs(direct_floor - expected_floor) < 0.05 * expected_floor,
        "open floor: E = I cos / r^2 = %.3f (got %.3f)" % (expected_floor, direct_floor))
t.check(t.point_rgb(out, "DirectIrradiance", under)[0] < 0.01 * direct_floor,
        "the floor under the sphere is in its shadow")
indirect_bottom = t.point_rgb(out, "IndirectIrradiance", bottom)
t.check(t.point_rgb(out, "DirectIrradiance", bottom)[0] == 0.0 and indirect_bottom[0] > 0.01,
        "the unlit bottom of the sphere receives light bounced off the floor (%.4f)"
        % indirect_bottom[0])
counters = {n: t.field_value(out, "LinkGI." + n) for n in ("LinkBuilds", "LightLinkBuilds", "BounceRuns")}
t.check(counters == {"LinkBuilds": 1, "LightLinkBuilds": 1, "BounceRuns": 1},
        "field data counters after the first update: %s" % counters)

# Moving the light recomputes direct light and bounces, not the links.
gi.LightPosition = [1, 3, 0]
gi.UpdatePipeline()
moved = t.fetch(gi)
t.check(t.field_value(moved, "LinkGI.LinkBuilds") == 1
        and t.field_value(moved, "LinkGI.LightLinkBuilds") == 2,
        "moving the light rebuilt the light links only")
t.check(abs(t.point_rgb(moved, "IndirectIrradiance", bottom)[0] - indirect_bottom[0]) > 1e-4,
        "moving the light changed the indirect light")

# A ParaView light proxy (as the Light Inspector makes) instead of the property light. It
# has VTK's default attenuation, which does not fall off: the top of the sphere receives I,
# where the property light (a lamp) gives I / r^2.
light = CreateLight()
light.Coords = "Scene"
light.Type = "Positional"
light.Position = [0, 3, 0]
light.ConeAngle = 180
light.Intensity = 9.0
gi.Light = 0
gi.AdditionalLights = [light]
gi.UpdatePipeline()
proxied = t.fetch(gi)
direct = t.point_rgb(proxied, "DirectIrradiance", top)[0]
t.check(abs(direct - 9.0) < 0.01 * 9.0 and abs(direct - direct_top * 1.7 ** 2) < 0.05 * direct,
        "a light proxy in AdditionalLights lights as VTK does, without falloff (%.4f)" % direct)
t.check(t.field_value(proxied, "LinkGI.LinkBuilds") == 1, "changing lights kept the links")

gi.RaysPerVertex = 64
gi.UpdatePipeline()
t.check(t.field_value(t.fetch(gi), "LinkGI.LinkBuilds") == 2, "changing the rays rebuilds the links")

# The sphere and the plane as two blocks: one scene, the same light as appended.
group = GroupDatasets(Input=[sphere, plane])
blocks = GlobalIllumination(Input=group, Light=0, AdditionalLights=[light], RaysPerVertex=64)
blocks.UpdatePipeline()
appended = t.fetch(gi)
leaves = []
iterator = t.fetch(blocks).NewIterator()
iterator.InitTraversal()
while not iterator.IsDoneWithTraversal():
    leaves.append(iterator.GetCurrentDataObject())
    iterator.GoToNextItem()
t.check(len(leaves) == 2 and all(leaf.IsA("vtkPolyData") for leaf in leaves),
        "a group of two surfaces gives a group of two lit surfaces")
first, worst = 0, 0.0
for leaf in leaves:
    for name in ("DirectIrradiance", "IndirectIrradiance"):
        for i in range(0, leaf.GetNumberOfPoints(), 7):
            a, b = t.point_rgb(leaf, name, i), t.point_rgb(appended, name, first + i)
            worst = max(worst, max(abs(x - y) / max(1.0, abs(y)) for x, y in zip(a, b)))
    first += leaf.GetNumberOfPoints()
t.check(first == appended.GetNumberOfPoints() and worst < 1e-5,
        "the blocks' arrays are those of the appended surface (largest difference %.2g)" % worst)
t.check(t.point_rgb(leaves[0], "IndirectIrradiance", bottom)[0] > 0.01,
        "light bounces from the plane's block onto the sphere's")
