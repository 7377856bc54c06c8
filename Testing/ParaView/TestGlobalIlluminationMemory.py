"""pvbatch: the filter proxy's MemoryBudget and ProxyVertices on a sphere over a plane.

The defaults (automatic budget, no proxy); a proxy of 1000 vertices lights every point, with
the direct light of the full surface (bit for bit) and bounced light that differs from the
full solve's but not by much; over the budget with no proxy asked for, a proxy that fits.
The Global Illumination representation, which solves in the background, does the same
with its Memory Budget: a render does not wait for it, and the solution drawn once it is
ready was solved on a proxy.
"""
from paraview.simple import *  # noqa: F401,F403 (the pvpython way)

import linkgi_paraview_testing as t

arguments = t.parse_arguments()
t.load_plugin(arguments.plugin, globals())

sphere = Sphere(Center=[0, 0.8, 0], Radius=0.5, ThetaResolution=48, PhiResolution=48)
plane = Plane(Origin=[-2, 0, -2], Point1=[-2, 0, 2], Point2=[2, 0, -2],  # normal +y
              XResolution=40, YResolution=40)
scene = AppendGeometry(Input=[sphere, plane])

gi = GlobalIllumination(Input=scene)
t.check(gi.MemoryBudget == 0.0 and gi.ProxyVertices == 0, "defaults: automatic budget, no proxy")
gi.LightType = "Point"
gi.LightPosition = [0, 3, 0]
gi.LightIntensity = 9.0
gi.RaysPerVertex = "64"
gi.UpdatePipeline()
full = t.fetch(gi)
n = full.GetNumberOfPoints()


def values(data, name):
    a = data.GetPointData().GetArray(name)
    return [a.GetTuple3(i) for i in range(a.GetNumberOfTuples())]


gi.ProxyVertices = 1000
gi.UpdatePipeline()
proxy = t.fetch(gi)
t.check(proxy.GetNumberOfPoints() == n, "the proxy lights every one of the %d points" % n)
t.check(values(proxy, "DirectIrradiance") == values(full, "DirectIrradiance"),
        "direct light on the full surface, as without the proxy")
a, b = values(proxy, "IndirectIrradiance"), values(full, "IndirectIrradiance")
error = sum((x[0] - y[0]) ** 2 for x, y in zip(a, b)) ** 0.5
norm = sum(y[0] ** 2 for y in b) ** 0.5
t.check(a != b and error < 0.2 * norm,
        "bounced light through the proxy within 20%% of the full solve (%.1f%%)" % (100 * error / norm))

# Over the budget with no proxy asked for: at 80% of what 256 rays are estimated to need
# (the link method's estimate, from a sample of its rows), the filter lights the surface
# through a proxy that fits (a warning, no error), with the same direct light.
# (A new filter each: a filter that keeps its surface would need less, its ray structures built.)
lamp = dict(LightType="Point", LightPosition=[0, 3, 0], LightIntensity=9.0, RaysPerVertex="256")
probe = GlobalIllumination(Input=scene, **lamp)
probe.UpdatePipeline()
estimate = t.fetch(probe).GetFieldData().GetAbstractArray("LinkGI.HostBytesEstimated").GetValue(0)
budgeted = GlobalIllumination(Input=scene, MemoryBudget=0.8 * float(estimate) / 2**20, **lamp)
budgeted.UpdatePipeline()
fitted = t.fetch(budgeted)
warnings = fitted.GetFieldData().GetAbstractArray("LinkGI.Warnings")
warnings = [warnings.GetValue(i) for i in range(warnings.GetNumberOfValues())] if warnings else []
t.check(any("lit through a proxy of about" in w for w in warnings),
        "over the budget (%.1f MiB of %.1f estimated): lit through a proxy (%s)"
        % (budgeted.MemoryBudget, float(estimate) / 2**20, warnings))
t.check(fitted.GetNumberOfPoints() == n and values(fitted, "DirectIrradiance") == values(full, "DirectIrradiance"),
        "lit through a proxy that fits, every point, the direct light unchanged")
t.check(max(v[0] for v in values(fitted, "IndirectIrradiance")) > 0.0, "and bounced light")

# Refinement through the proxy: a plane of 2 x 2 cells under the lamp is refined where the
# light asks for it, within the vertex budget, and every output point carries the light.
coarse = GlobalIllumination(Input=Plane(Origin=[-2, 0, -2], Point1=[-2, 0, 2], Point2=[2, 0, -2],
                                        XResolution=2, YResolution=2))
t.check(coarse.Refinement == 0 and coarse.RefinementRounds == 3, "refinement off by default")
coarse.LightType = "Point"
coarse.LightPosition = [1, 1, 0.5]
coarse.LightIntensity = 4.0
coarse.RaysPerVertex = "16"
coarse.Refinement = 1
coarse.RefinementMaxVertices = 300
coarse.UpdatePipeline()
refined = t.fetch(coarse)
t.check(9 < refined.GetNumberOfPoints() <= 300,
        "refined from 9 to %d points (budget 300)" % refined.GetNumberOfPoints())
t.check(refined.GetPointData().GetArray("DirectIrradiance").GetNumberOfTuples() == refined.GetNumberOfPoints(),
        "light on every refined point")

# The representation over the budget: a finer surface (40k points, whose decimation alone
# takes longer than a render) solved in the background (Wait = Never: the render returns at
# once), then drawn lit through a proxy.
fine = AppendGeometry(Input=[Sphere(Center=[0, 0.8, 0], Radius=0.5, ThetaResolution=200, PhiResolution=200),
                             plane])
fine.UpdatePipeline()
n = fine.GetDataInformation().GetNumberOfPoints()
view = CreateView("RenderView")
view.ViewSize = [200, 200]
shown = Show(fine, view)
shown.Representation = "Global Illumination"
shown.GlobalIlluminationRays = 256
shown.GlobalIlluminationMemoryBudget = 20.0
shown.GlobalIlluminationWait = "Never"
Render(view)


def information(name):
    shown.SMProxy.UpdatePropertyInformation()
    return shown.SMProxy.GetProperty("GlobalIllumination" + name).GetElement(0)


newest, drawn = information("NewestRequest"), information("ShownRequest")
t.check(newest > drawn, "the render returned before the solution (request %d, drawn %d)" % (newest, drawn))
shown.GlobalIlluminationWait = "Always"
Render(view)
solved = information("SolvedElements")
t.check(information("ShownRequest") == information("NewestRequest") and information("LastError") == "",
        "the solution drawn, without error: %s" % information("LastError"))
t.check(0 < solved < n, "solved on a proxy of %d of the %d points" % (solved, n))
t.check(information("MeanIndirect") > 0.0, "with bounced light on the surface")
