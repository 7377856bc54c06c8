"""pvbatch: implicit visibility through the plugin, on the filter proxy and the representation.

1. The Global Illumination filter on a sphere over a plane, lit by a point light: Method
   "Implicit Visibility" reports itself and its stages (LinkGI.Method, LinkGI.MsImplicitLinks,
   no link-ray stage), the same direct light as the links and an indirect light within 20%
   of theirs on average; ImplicitVisibilityBins re-links without new shadow rays.
2. The Global Illumination representation of the Cornell box: its Method drop-down runs
   implicit visibility (no link rays built, indirect light on the walls).
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
gi.LightType = "Point"
gi.LightPosition = [0.5, 3, 0.2]
gi.LightIntensity = 9.0
gi.Backend = "CPU"
gi.UpdatePipeline()
links = t.fetch(gi)

gi.Method = "Implicit Visibility"
gi.ImplicitVisibilityBins = 8
gi.UpdatePipeline()
iv = t.fetch(gi)
t.check(text_field(iv, "LinkGI.Method") == "implicit-visibility", "Implicit Visibility ran that method")
t.check(iv.GetFieldData().GetArray("LinkGI.MsImplicitLinks") is not None
        and iv.GetFieldData().GetArray("LinkGI.MsLinks") is None,
        "its own stages are in the field data, the link-ray stage is not")
direct = abs(mean(iv, "DirectIrradiance") / mean(links, "DirectIrradiance") - 1)
t.check(direct < 1e-5, "the same direct light (the shared stage): %.2g" % direct)
ratio = mean(iv, "IndirectIrradiance") / mean(links, "IndirectIrradiance")
t.check(abs(ratio - 1) < 0.2, "indirect light within 20%% of the links': ratio %.3f" % ratio)
gi.ImplicitVisibilityBins = 12
gi.UpdatePipeline()
again = t.fetch(gi)
t.check(t.field_value(again, "LinkGI.ImplicitLinkBuilds") == 2
        and t.field_value(again, "LinkGI.LightLinkBuilds") == 1,
        "more bins re-link and keep the shadow rays")

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
display.GlobalIlluminationMethod = "Implicit Visibility"
Render(view)


def statistic(name):
    proxy = display.SMProxy
    proxy.UpdatePropertyInformation()
    return proxy.GetProperty("GlobalIllumination" + name).GetElement(0)


t.check(statistic("LinkBuilds") == 0 and statistic("MeanIndirect") > 0.0,
        "the representation ran implicit visibility: no link rays, light on the walls")
