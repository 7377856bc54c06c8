"""pvbatch: the plugin's Method drop-down, on the filter proxy and on the representation.

1. The Global Illumination filter on a sphere over a plane, lit by a point light: Links by
   default; Instant Radiosity gives the same three point arrays, reports itself and its
   stages in the field data (LinkGI.Method, LinkGI.VplBuilds, no link stage), the same
   direct light and an indirect light within 15% of the links' on average; so does photon
   mapping, and the links' indirect light is within 15% of the Reference path tracer's.
2. The Global Illumination representation of the Cornell box: its Method drop-down runs
   instant radiosity (no links built, indirect light on the walls); back to Links builds
   the links.
"""
from paraview.simple import *  # noqa: F401,F403 (the pvpython way)

import linkgi_paraview_testing as t

arguments = t.parse_arguments()
t.load_plugin(arguments.plugin, globals())


def text_field(data, name):
    array = data.GetFieldData().GetAbstractArray(name)
    if array is None:
        t.fail("field data %s is missing" % name)
    return array.GetValue(0)


def mean(data, name):
    array = data.GetPointData().GetArray(name)
    n = array.GetNumberOfTuples()
    return sum(array.GetComponent(i, 0) for i in range(n)) / n


# 1. The filter proxy.
sphere = Sphere(Center=[0, 0.8, 0], Radius=0.5, ThetaResolution=32, PhiResolution=32)
plane = Plane(Origin=[-2, 0, -2], Point1=[-2, 0, 2], Point2=[2, 0, -2],  # normal +y
              XResolution=30, YResolution=30)
gi = GlobalIllumination(Input=AppendGeometry(Input=[sphere, plane]))
t.check(gi.Method == "Links", "the default method is Links")
gi.LightType = "Point"
gi.LightPosition = [0.5, 3, 0.2]
gi.LightIntensity = 9.0
gi.Backend = "CPU"
gi.UpdatePipeline()
links = t.fetch(gi)
t.check(text_field(links, "LinkGI.Method") == "links", "Links ran the link method")

gi.Method = "Instant Radiosity"
gi.NumberOfVPLs = 2048
gi.UpdatePipeline()
ir = t.fetch(gi)
t.check(text_field(ir, "LinkGI.Method") == "instant-radiosity", "Instant Radiosity ran that method")
t.check(ir.GetFieldData().GetArray("LinkGI.VplBuilds") is not None
        and ir.GetFieldData().GetArray("LinkGI.MsLinks") is None,
        "its own stages are in the field data, the link stages are not")
for name in ("DirectIrradiance", "IndirectIrradiance", "Radiance"):
    t.check(ir.GetPointData().GetArray(name).GetNumberOfTuples() == ir.GetNumberOfPoints(),
            "point array %s" % name)
direct = abs(mean(ir, "DirectIrradiance") / mean(links, "DirectIrradiance") - 1)
t.check(direct < 1e-5, "the same direct light (the shared stage): %.2g" % direct)
ratio = mean(ir, "IndirectIrradiance") / mean(links, "IndirectIrradiance")
t.check(abs(ratio - 1) < 0.15, "indirect light within 15%% of the links': ratio %.3f" % ratio)

gi.Method = "Photon Mapping"
gi.NumberOfPhotons = 65536
gi.NumberOfClusters = 512
gi.UpdatePipeline()
pm = t.fetch(gi)
t.check(text_field(pm, "LinkGI.Method") == "photon-mapping", "Photon Mapping ran that method")
t.check(pm.GetFieldData().GetArray("LinkGI.PhotonTraces") is not None
        and pm.GetFieldData().GetArray("LinkGI.ClusterBuilds") is not None,
        "its photon and cluster stages are in the field data")
ratio = mean(pm, "IndirectIrradiance") / mean(links, "IndirectIrradiance")
t.check(abs(ratio - 1) < 0.15, "photon mapping's indirect light within 15%% of the links': ratio %.3f" % ratio)

gi.Method = "Reference"
gi.ReferencePathsPerVertex = 256
gi.UpdatePipeline()
reference = t.fetch(gi)
t.check(text_field(reference, "LinkGI.Method") == "reference", "Reference ran the path tracer")
paths = reference.GetFieldData().GetArray("LinkGI.Paths")
t.check(paths is not None and paths.GetValue(0) == 256 * reference.GetNumberOfPoints(),
        "its paths are counted: 256 per vertex")
ratio = mean(links, "IndirectIrradiance") / mean(reference, "IndirectIrradiance")
t.check(abs(ratio - 1) < 0.15, "the links' indirect light within 15%% of the reference: ratio %.3f" % ratio)

# 2. The representation.
view = CreateView("RenderView")
view.ViewSize = [200, 200]
view.UseLight = 0
light = CreateLight()
light.Coords = "Scene"
light.Type = "Positional"
light.Position = [0.278, 0.4488, 0.2795]
light.ConeAngle = 180
view.AdditionalLights = [light]
box = GlobalIlluminationScene(Scene="cornell")
display = Show(box, view)
display.Representation = "Global Illumination"
display.GlobalIlluminationMethod = "Instant Radiosity"
Render(view)


def statistic(name):
    proxy = display.SMProxy
    proxy.UpdatePropertyInformation()
    return proxy.GetProperty("GlobalIllumination" + name).GetElement(0)


t.check(statistic("LinkBuilds") == 0 and statistic("MeanIndirect") > 0.0,
        "the representation ran instant radiosity: no links, light on the walls")
display.GlobalIlluminationMethod = "Links"
Render(view)
# Once per stage: where the process's last link update predicts a long one (a loaded
# machine), a progressive coarse stage builds its own links before the final's.
t.check(statistic("LinkBuilds") >= 1 and statistic("LinkBuilds") == statistic("ShownStages"),
        "back to Links builds the links, once per stage: %d builds, %d stages"
        % (statistic("LinkBuilds"), statistic("ShownStages")))
