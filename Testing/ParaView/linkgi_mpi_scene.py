"""The scene and checks shared by the MPI tests (TestGlobalIlluminationMPI.py under
`mpirun pvbatch --mpi`, TestGlobalIlluminationPVServer.py against `mpiexec pvserver`).

A block floats over a floor under a point light; with 2 or more ranks the block is rank 0's
partition and the floor rank 1's (ranks beyond have no points), so the block's shadow on
the floor and the light between them cross the partition boundary.

run() checks, after connecting and loading the plugin:
1. Direct light only: the block's shadow is on the floor (a shadowed floor pixel is far
   darker than a lit one) and the picture matches the one baseline that the one-rank run
   matches too. Without the other ranks' triangles in each rank's shadow maps
   (vtkGlobalIlluminationGlobalCasters) rank 1 would draw a floor without the shadow.
2. The representation's counters (pvbatch only: a client reads its own copy): on rank 0
   the shadow maps hold the floor's triangles (the other ranks'), exchanged once, not again
   on further renders or a light move; the light move re-runs the filter's light links and
   bounces only, and the filter received the other ranks' partitions.
3. The size limit: with none of the other ranks' triangles allowed, each rank's maps hold
   its own partition only (a warning says so) and the floor of rank 1 loses the block's
   shadow; one rank keeps it.
4. With a small limit the ranks exchange decimated proxies and the shadow is back.
"""
import os

from paraview.simple import (CreateLight, CreateView, ProgrammableSource, Render,
                             SaveScreenshot, Show)

import linkgi_paraview_testing as t

# The scene, made on every rank: piece 0 is the block, piece 1 the floor (one piece: both).
SCENE = """
from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline as sddp
from vtkmodules.vtkFiltersCore import vtkAppendPolyData, vtkTriangleFilter
from vtkmodules.vtkFiltersSources import vtkPlaneSource
info = self.GetOutputInformation(0)
piece = info.Get(sddp.UPDATE_PIECE_NUMBER())
pieces = info.Get(sddp.UPDATE_NUMBER_OF_PIECES())
def plane(origin, p1, p2, n):
    s = vtkPlaneSource()
    s.SetOrigin(origin); s.SetPoint1(p1); s.SetPoint2(p2)
    s.SetResolution(n, n)
    return s
parts = []
if piece == 0:  # the block: x, y in [-0.25, 0.25], z in [0.3, 0.8], faces outward
    lo, hi, z0, z1 = -0.25, 0.25, 0.3, 0.8
    parts += [plane((lo, lo, z0), (lo, hi, z0), (hi, lo, z0), 6),
              plane((lo, lo, z1), (hi, lo, z1), (lo, hi, z1), 6),
              plane((lo, lo, z0), (hi, lo, z0), (lo, lo, z1), 6),
              plane((lo, hi, z0), (lo, hi, z1), (hi, hi, z0), 6),
              plane((lo, lo, z0), (lo, lo, z1), (lo, hi, z0), 6),
              plane((hi, lo, z0), (hi, hi, z0), (hi, lo, z1), 6)]
if piece == (1 if pieces > 1 else 0):  # the floor, facing up
    parts.append(plane((-1.5, -1.5, 0.0), (1.5, -1.5, 0.0), (-1.5, 1.5, 0.0), 40))
append = vtkAppendPolyData()
for p in parts:
    append.AddInputConnection(p.GetOutputPort())
if parts:
    triangles = vtkTriangleFilter()
    triangles.SetInputConnection(append.GetOutputPort())
    triangles.Update()
    self.GetOutput().ShallowCopy(triangles.GetOutput())
"""


def run(arguments, ranks, counters_here=True, name="TestGlobalIlluminationMPI"):
    """The checks; `counters_here` says whether the representation's information
    properties are rank 0's (pvbatch), not a client's own copy (client-server: the
    images and shadows are still checked)."""
    source = ProgrammableSource(OutputDataSetType="vtkPolyData", Script=SCENE)

    view = CreateView("RenderView")
    view.ViewSize = [320, 320]
    view.OrientationAxesVisibility = 0
    view.UseLight = 0
    view.UseColorPaletteForBackground = 0
    view.Background = [0.0, 0.0, 0.0]
    light = CreateLight()
    light.Coords = "Scene"
    light.Type = "Positional"
    light.Position = [0.5, 0.3, 2.0]
    light.ConeAngle = 180
    light.Intensity = 4.0
    view.AdditionalLights = [light]

    display = Show(source, view)
    display.Representation = "Global Illumination"
    display.DiffuseColor = [0.8, 0.8, 0.8]
    display.GlobalIlluminationRays = 64
    display.GlobalIlluminationBounces = 2
    display.GlobalIlluminationDisplayMode = "Direct"
    display.GlobalIlluminationLightFalloff = "Inverse Square"  # the light is a lamp: 1/r^2
    display.GlobalIlluminationToneMapping = "Hue Preserving"
    view.CameraPosition = [0.0, -3.0, 3.2]
    view.CameraFocalPoint = [0.0, 0.0, 0.2]
    view.CameraViewUp = [0.0, 0.0, 1.0]
    view.CameraViewAngle = 30

    Render(view)

    def counters():
        proxy = display.SMProxy
        proxy.UpdatePropertyInformation()
        return {n: proxy.GetProperty("GlobalIllumination" + n).GetElement(0)
                for n in ("GlobalCasterTriangles", "GlobalCasterGathers", "ShadowMapRenders",
                          "LinkBuilds", "LightLinkBuilds", "BounceRuns", "PartitionBytes",
                          "Updates")}

    def floor_pixel(world, image):
        """The image's grey value at the world point `world` on the floor."""
        renderer = view.GetRenderer()
        renderer.SetWorldPoint(world[0], world[1], world[2], 1.0)
        renderer.WorldToDisplay()
        x, y, _ = renderer.GetDisplayPoint()
        return image.GetScalarComponentAsDouble(int(round(x)), int(round(y)), 0, 0)

    def shadow_and_lit(name):
        """The screenshot <name>.png's grey values in the block's shadow and in the open: the
        light at (0.4-0.5, 0.3, 2) casts the block's shadow over about x in [-0.7, 0.2], y in
        [-0.6, 0.2] of the floor; (-0.5, -0.3, 0) lies in it, beside the block as the camera
        sees it; (1, 1, 0) is lit."""
        from vtkmodules.vtkIOImage import vtkPNGReader

        path = os.path.join(arguments.output_dir, name + ".png")
        if not os.path.exists(path):
            SaveScreenshot(path, view, ImageResolution=list(view.ViewSize), TransparentBackground=0)
        reader = vtkPNGReader()
        reader.SetFileName(path)
        reader.Update()
        values = (floor_pixel((-0.5, -0.3, 0.0), reader.GetOutput()),
                  floor_pixel((1.0, 1.0, 0.0), reader.GetOutput()))
        print("%s: floor shadowed %.1f, lit %.1f" % ((name,) + values))
        return values


    def shadow_and_lit_at_limit(limit, image):
        """shadow_and_lit of a new screenshot after setting the caster limit."""
        display.GlobalIlluminationMaximumGlobalCasterTriangles = limit
        Render(view)
        path = os.path.join(arguments.output_dir, image + ".png")
        if os.path.exists(path):
            os.remove(path)
        return shadow_and_lit(image)

    # 1. The shadow.
    t.compare_with_baseline(view, name, arguments)
    shadowed, lit = shadow_and_lit(name)
    t.check(lit > 40.0 and shadowed < 0.25 * lit,
            "the block's shadow is on the floor (%.1f against %.1f lit)" % (shadowed, lit))

    if counters_here:
        # 2. The other ranks' triangles: the floor's 2 * 40 * 40 on rank 0, exchanged once.
        c = counters()
        print("counters on rank 0: %s" % c)
        expected = 3200 if ranks > 1 else 0
        t.check(c["GlobalCasterTriangles"] == expected,
                "rank 0's shadow maps hold the %d triangles of the other ranks" % expected)
        t.check(c["GlobalCasterGathers"] == (1 if ranks > 1 else 0), "the triangles were exchanged once")
        light.Position = [0.4, 0.3, 2.0]
        Render(view)
        view.CameraPosition = [0.1, -3.0, 3.2]
        Render(view)
        c2 = counters()
        t.check(c2["GlobalCasterGathers"] == c["GlobalCasterGathers"],
                "a light move and a camera move exchange no triangles")
        t.check(c2["ShadowMapRenders"] == c["ShadowMapRenders"] + 1,
                "the light move re-rendered the shadow maps once, the camera move not")
        print("counters after the moves: %s" % c2)
        # (c counts a coarse stage's links too where the first solve had one: one rank
        # solves in the background, with progressive stages.)
        t.check(c2["LinkBuilds"] == c["LinkBuilds"]
                and c2["LightLinkBuilds"] == c["LightLinkBuilds"] + 1
                and c2["BounceRuns"] == c["BounceRuns"] + 1,
                "the light move re-ran light links and bounces only, the camera move nothing")
        t.check(c["Updates"] == 1 and c2["Updates"] == 2,
                "two solutions drawn: the first and the light move's (%d, %d)"
                % (c["Updates"], c2["Updates"]))
        t.check((c["PartitionBytes"] > 0) == (ranks > 1),
                "the filter received %d bytes of the other ranks' partitions (none on one rank)"
                % c["PartitionBytes"])
    else:
        light.Position = [0.4, 0.3, 2.0]
        Render(view)

    # 3. The size limit: with none of the other ranks' triangles allowed, each rank's maps hold
    # its own partition only (a warning says so), and the floor of rank 1 loses the block's
    # shadow; one rank keeps it.
    shadowed, lit = shadow_and_lit_at_limit(0, name + "Limit")
    if counters_here:
        c3 = counters()
        t.check(c3["GlobalCasterTriangles"] == 0, "past the limit no triangles are drawn")
    if ranks > 1:
        t.check(shadowed > 0.5 * lit, "past the limit the shadow across the partitions is missing")
    else:
        t.check(shadowed < 0.25 * lit, "one rank keeps its shadow past the limit")

    # 4. Proxies: with a limit of 200 triangles, each rank sends a decimated proxy of its
    # partition (the block's 432 triangles become at most 200 / (ranks - 1)); the floor of
    # rank 1 gets the block's shadow back, approximately.
    if ranks > 1:
        shadowed, lit = shadow_and_lit_at_limit(200, name + "Proxy")
        t.check(shadowed < 0.25 * lit,
                "with proxies the shadow across the partitions is back (%.1f against %.1f lit)"
                % (shadowed, lit))
        if counters_here:
            c4 = counters()
            t.check(0 < c4["GlobalCasterTriangles"] <= 200,
                    "rank 0 drew %d proxy triangles, at most the limit"
                    % c4["GlobalCasterTriangles"])


def check_arrays(arguments, ranks, plugin, write=None, reference=None):
    """The Global Illumination filter proxy on the same partitioned scene (point light as
    above, 64 rays, 2 bounces): writes its output's arrays (`write`, the one-rank run) or
    compares them with those (`reference`): the same points in the same order (the block,
    then the floor, as one rank appends them and Fetch merges the ranks' pieces), and every
    array within 1e-4 of the one-rank value, relative to that array's largest value.
    `plugin`: the namespace the plugin was loaded into."""
    from paraview.simple import Delete
    from vtkmodules.vtkIOXML import vtkXMLPolyDataReader, vtkXMLPolyDataWriter

    source = ProgrammableSource(OutputDataSetType="vtkPolyData", Script=SCENE)
    gi = plugin["GlobalIllumination"](Input=source)
    gi.LightType = "Point"
    gi.LightPosition = [0.5, 0.3, 2.0]
    gi.LightIntensity = 4.0
    gi.RaysPerVertex = "64"
    gi.NumberOfBounces = 2
    gi.UpdatePipeline()
    out = t.fetch(gi)
    print("arrays on %d ranks: %d points" % (ranks, out.GetNumberOfPoints()))
    if write:
        writer = vtkXMLPolyDataWriter()
        writer.SetFileName(write)
        writer.SetInputData(out)
        t.check(writer.Write() == 1, "one-rank arrays written to %s" % write)
    if reference:
        reader = vtkXMLPolyDataReader()
        reader.SetFileName(reference)
        reader.Update()
        ref = reader.GetOutput()
        n = ref.GetNumberOfPoints()
        t.check(n > 0 and out.GetNumberOfPoints() == n,
                "%d points, as on one rank (%d)" % (out.GetNumberOfPoints(), n))
        worst = max(max(abs(a - b) for a, b in zip(out.GetPoint(i), ref.GetPoint(i)))
                    for i in range(n))
        t.check(worst <= 1e-6, "the same points in the same order (worst %.2g)" % worst)
        for name in ("DirectIrradiance", "IndirectIrradiance", "Radiance"):
            mine, theirs = out.GetPointData().GetArray(name), ref.GetPointData().GetArray(name)
            t.check(mine is not None and theirs is not None, "%s on both" % name)
            scale = max(max(abs(v) for v in theirs.GetRange(c)) for c in range(3)) or 1.0
            error = max(abs(mine.GetComponent(i, c) - theirs.GetComponent(i, c))
                        for i in range(n) for c in range(3)) / scale
            t.check(error <= 1e-4, "%s equals the one-rank array (%.2g relative)" % (name, error))
    Delete(gi)
    Delete(source)
