"""Every method at its default settings against the reference path tracer on the dining room
(dining-room-scene.py), lit by one point lamp in a pendant shade above the table, through
the filter on the CPU.

    PYTHONPATH=build/lib/python3.11/dist-packages /usr/bin/python3 \\
      Documentation/scripts/dining-room-agreement.py SCENE.vtp [PATHS] [REPEATS]

PATHS (default 1024) is the reference's paths per vertex; it runs with seeds 0 and 1, and
their difference is its own noise (the error of one seed against the mean of two is about
half of it, taken as the reference's error). REPEATS (default 1): each method's update is
timed so many times, in a new filter each, and the median printed.

Printed per method, over the whole scene, each area-weighted and in luminance (Rec. 709):
`total`, the relative RMSE of direct + indirect irradiance (the error of
filters.TestGlobalIlluminationAgreement); `indirect`, that of the indirect irradiance alone;
`bias`, the mean indirect irradiance over the reference's, less 1; the total and the
indirect light also with the lamp's own shade aside (its inside, 15-20 cm from the lamp, is
94% of the scene's squared irradiance, so it decides the whole scene's figures). Then, per
method, the parts (scene.xml's order) that hold most of its squared error.
"""
import statistics
import sys
import time

import linkgi
import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
from vtkmodules.vtkRenderingCore import vtkLight

from agreement import LUMINANCE, rel_rmse, vertex_areas

# The middle of the opening of the shade above the table's right half (Mesh013, whose rim is at
# 1.213 m), 2 cm under it, in the scene's metres.
LAMP = (0.95 / 3, 3.60 / 3, -1.945 / 3)
SHADE = 0  # the lamp's shade, part 0 (Mesh013): its inside, 15-20 cm from the lamp, is 94% of sum A E^2
METHODS = [name for name in linkgi.methods() if name != "reference"]  # against the reference


def read(path):
    reader = vtkXMLPolyDataReader()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


def lamp():
    light = vtkLight()
    light.SetPositional(True)
    light.SetConeAngle(180)
    light.SetAttenuationValues(0, 0, 1)
    light.SetPosition(*LAMP)
    light.SetIntensity(1.0)
    return light


def solve(surface, method, paths=1024, seed=0):
    """(direct, indirect) luminance per point, the update's seconds and the filter's output."""
    gi = linkgi.vtkGlobalIlluminationFilter()
    gi.SetInputData(surface)
    gi.AddLight(lamp())
    gi.SetAlbedoArrayName("Albedo")
    gi.SetBackendToCPU()
    gi.SetMethod(linkgi.methods()[method])
    gi.SetReferencePathsPerVertex(paths)
    gi.SetSeed(seed)
    start = time.perf_counter()
    gi.Update()
    seconds = time.perf_counter() - start
    out = gi.GetOutput()
    arrays = [vtk_to_numpy(out.GetPointData().GetArray(n)) @ LUMINANCE for n in ("DirectIrradiance", "IndirectIrradiance")]
    return arrays[0], arrays[1], seconds, out


def warnings(out):
    w = out.GetFieldData().GetAbstractArray("LinkGI.Warnings")
    return [w.GetValue(i) for i in range(w.GetNumberOfValues())] if w else []


def main(path, paths, repeats):
    surface = read(path)
    areas = vertex_areas(surface)
    part = vtk_to_numpy(surface.GetPointData().GetArray("Part"))
    print("%s: %d points, %d triangles, %.1f m^2; reference %d paths per vertex"
          % (path, surface.GetNumberOfPoints(), surface.GetNumberOfPolys(), areas.sum(), paths))
    d0, i0, t0, out = solve(surface, "reference", paths, 0)
    d1, i1, t1, _ = solve(surface, "reference", paths, 1)
    for w in warnings(out):
        print("  warning:", w)
    rd, ri = d0, (i0 + i1) / 2
    rest = part != SHADE
    print("reference: %.1f s and %.1f s; seed 0 against seed 1: total %.2f%% (shade aside %.2f%%), indirect %.2f%% "
          "(%.2f%%), mean indirect %+.2f%%"
          % (t0, t1, 100 * rel_rmse(d0 + i0, d1 + i1, areas), 100 * rel_rmse((d0 + i0)[rest], (d1 + i1)[rest], areas[rest]),
             100 * rel_rmse(i0, i1, areas), 100 * rel_rmse(i0[rest], i1[rest], areas[rest]),
             100 * (np.sum(areas * i0) / np.sum(areas * i1) - 1)))
    print("  mean direct %.4g, mean indirect %.4g (area-weighted luminance)"
          % (np.sum(areas * rd) / areas.sum(), np.sum(areas * ri) / areas.sum()))
    print("| method | total | total, shade aside | indirect | indirect, shade aside | mean indirect | update |")
    print("|---|---|---|---|---|---|---|")
    details = {}
    for method in METHODS:
        d, i, seconds, out = solve(surface, method)
        times = [seconds] + [solve(surface, method)[2] for _ in range(repeats - 1)]
        print("| %s | %.1f%% | %.1f%% | %.1f%% | %.1f%% | %+.1f%% | %.2f s |"
              % (method, 100 * rel_rmse(d + i, rd + ri, areas), 100 * rel_rmse((d + i)[rest], (rd + ri)[rest], areas[rest]),
                 100 * rel_rmse(i, ri, areas), 100 * rel_rmse(i[rest], ri[rest], areas[rest]),
                 100 * (np.sum(areas * i) / np.sum(areas * ri) - 1), statistics.median(times)))
        details[method] = (d, i, warnings(out))
    for method, (d, i, ws) in details.items():
        print("\n%s: direct against the reference's %.2f%%; %s" % (method, 100 * rel_rmse(d, rd, areas),
                                                                   "; ".join(ws) or "no warnings"))
        print("  part: area, share of the reference's squared total, its indirect error (rel. RMSE), bias")
        share = {}
        for p in np.unique(part):
            m = part == p
            share[p] = np.sum(areas[m] * (d[m] + i[m] - rd[m] - ri[m]) ** 2)
        total = sum(share.values())
        for p in sorted(share, key=share.get, reverse=True)[:6]:
            m = part == p
            print("  part %2d: %.2f m^2, %4.1f%% of the squared error, indirect %.1f%%, mean indirect %+.1f%%"
                  % (p, areas[m].sum(), 100 * share[p] / total, 100 * rel_rmse(i[m], ri[m], areas[m]),
                     100 * (np.sum(areas[m] * i[m]) / np.sum(areas[m] * ri[m]) - 1)))


if __name__ == "__main__":
    main(sys.argv[1], int(sys.argv[2]) if len(sys.argv) > 2 else 1024, int(sys.argv[3]) if len(sys.argv) > 3 else 1)
