"""Every method against the reference path tracer on a model alone (no room around it), lit
by one point light 1.4 bounding-box diagonals away, through the filter on the CPU.

    PYTHONPATH=build/lib/python3.11/dist-packages /usr/bin/python3 \\
      Documentation/scripts/no-room-agreement.py [--refine] MODEL...

MODEL: a .vtp, .vtk (legacy), .ply, .stl, .obj or .g (BYU) file; its surface is extracted and
triangulated. Each method runs at its default settings but for light oversampling, which
filters shadow edges on purpose (off here, as in the reference, so direct light agrees
exactly); the reference has 1024 paths per vertex, and its seeds 0 and 1 are compared for its
own noise. --refine: each method with Refinement on, against the reference on the surface
it refined, with the normals it was lit with. Printed per method, area-weighted and in luminance: the relative RMSE of the
total and of the indirect irradiance, the bias of the mean indirect irradiance, the update's
seconds.
"""
import math
import sys
import time

import linkgi
import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkFiltersCore import vtkTriangleFilter
from vtkmodules.vtkFiltersGeometry import vtkDataSetSurfaceFilter
from vtkmodules.vtkIOGeometry import vtkBYUReader, vtkOBJReader, vtkSTLReader
from vtkmodules.vtkIOLegacy import vtkDataSetReader
from vtkmodules.vtkIOPLY import vtkPLYReader
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
from vtkmodules.vtkRenderingCore import vtkLight

from agreement import LUMINANCE, rel_rmse, vertex_areas

READERS = {"vtp": vtkXMLPolyDataReader, "vtk": vtkDataSetReader, "ply": vtkPLYReader, "stl": vtkSTLReader,
           "obj": vtkOBJReader, "g": vtkBYUReader}
METHODS = [name for name in linkgi.methods() if name != "reference"]


def read(path):
    reader = READERS[path.rsplit(".", 1)[1].lower()]()
    (reader.SetGeometryFileName if isinstance(reader, vtkBYUReader) else reader.SetFileName)(path)
    surface = vtkDataSetSurfaceFilter()
    surface.SetInputConnection(reader.GetOutputPort())
    triangles = vtkTriangleFilter()
    triangles.SetInputConnection(surface.GetOutputPort())
    triangles.Update()
    return triangles.GetOutput()


def lamp(surface):
    b = surface.GetBounds()
    centre = [(b[2 * k] + b[2 * k + 1]) / 2 for k in range(3)]
    diagonal = math.sqrt(sum((b[2 * k + 1] - b[2 * k]) ** 2 for k in range(3)))
    light = vtkLight()
    light.SetPositional(True)
    light.SetConeAngle(180)
    light.SetPosition(*[c + f * diagonal for c, f in zip(centre, (0.6, 0.8, 1.0))])
    light.SetFocalPoint(*centre)
    return light


def solve(surface, light, method, refine=False, seed=0):
    """(direct, indirect) luminance per point, the output surface and the update's seconds."""
    gi = linkgi.vtkGlobalIlluminationFilter()
    gi.SetInputData(surface)
    gi.AddLight(light)
    gi.SetBackendToCPU()
    gi.SetMethod(linkgi.methods()[method])
    gi.SetLightOversampling(False)
    gi.SetRefinement(refine)
    gi.SetReferencePathsPerVertex(1024)
    gi.SetSeed(seed)
    start = time.perf_counter()
    gi.Update()
    seconds = time.perf_counter() - start
    out = gi.GetOutput()
    light_arrays = [vtk_to_numpy(out.GetPointData().GetArray(n)) @ LUMINANCE
                    for n in ("DirectIrradiance", "IndirectIrradiance")]
    return light_arrays[0], light_arrays[1], out, seconds


def geometry(surface):
    """The surface's points and cells, and the normals it was lit with (a refined surface's)."""
    copy = surface.NewInstance()
    copy.CopyStructure(surface)
    normals = surface.GetPointData().GetNormals()
    if normals is not None:
        copy.GetPointData().SetNormals(normals)
    return copy


def main(paths, refine):
    for path in paths:
        surface = read(path)
        light = lamp(surface)
        rd, ri, out, _ = solve(surface, light, "reference")
        d1, i1, _, _ = solve(surface, light, "reference", seed=1)
        w = vertex_areas(out)
        print("%s: %d points; mean direct %.4g, indirect %.4g; the reference's seeds 0 and 1: total %.1f%%, "
              "indirect %.1f%%" % (path, out.GetNumberOfPoints(), np.sum(w * rd) / w.sum(), np.sum(w * ri) / w.sum(),
                                   100 * rel_rmse(d1 + i1, rd + ri, w), 100 * rel_rmse(i1, ri, w)))
        for method in METHODS:
            d, i, out, seconds = solve(surface, light, method, refine)
            points = ""
            if refine:  # the reference on the surface this method refined
                rd_m, ri_m, _, _ = solve(geometry(out), light, "reference")
                w_m = vertex_areas(out)
                points = ", refined to %d points" % out.GetNumberOfPoints()
            else:
                rd_m, ri_m, w_m = rd, ri, w
            print("  %-20s total %.1f%%, indirect %.1f%%, mean indirect %+.1f%%, %.2f s%s"
                  % (method, 100 * rel_rmse(d + i, rd_m + ri_m, w_m), 100 * rel_rmse(i, ri_m, w_m),
                     100 * (np.sum(w_m * i) / np.sum(w_m * ri_m) - 1), seconds, points))


if __name__ == "__main__":
    refine = "--refine" in sys.argv[1:]
    main([a for a in sys.argv[1:] if a != "--refine"], refine)
