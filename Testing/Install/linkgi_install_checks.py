"""Checks shared by the tests of an installed LinkGI (Testing/Install)."""
import os
import sys


def check(condition, message):
    if not condition:
        sys.exit("FAILED: " + message)
    print("ok: " + message)


def check_inside(prefix, paths, what):
    """Every one of `paths` (files a process loaded) lies in `prefix`."""
    prefix = os.path.realpath(prefix)
    outside = sorted(p for p in paths if not os.path.realpath(p).startswith(prefix + os.sep))
    check(paths and not outside, "%s from %s (outside it: %s)" % (what, prefix, outside))


def check_sphere_on_plane(path):
    """The scene of the examples GlobalIlluminationSphereOnPlane and sphere_on_plane.py as
    written to `path`: the three point arrays, lit, and the direct light of the point light
    (16 W/sr, 4 m above the plane at x = y = 0.5) on the plane vertex nearest the foot of
    the light: I cos(theta) / r^2, 1 right below it."""
    from vtkmodules.vtkIOXML import vtkXMLPolyDataReader

    reader = vtkXMLPolyDataReader()
    reader.SetFileName(path)
    reader.Update()
    data = reader.GetOutput()
    for name in ("DirectIrradiance", "IndirectIrradiance", "Radiance"):
        array = data.GetPointData().GetArray(name)
        check(array is not None and array.GetNumberOfTuples() == data.GetNumberOfPoints()
              and array.GetRange(0)[1] > 0, "point array %s, lit" % name)
    below = data.FindPoint(0.5, 0.5, 0.0)
    x, y, _ = data.GetPoint(below)
    r2 = (0.5 - x) ** 2 + (0.5 - y) ** 2 + 4.0 ** 2
    expected = 16.0 * 4.0 / r2 ** 1.5  # cos(theta) = 4 / r
    direct = data.GetPointData().GetArray("DirectIrradiance").GetTuple3(below)
    check(all(abs(e - expected) < 1e-3 * expected for e in direct),
          "direct irradiance below the light %s = I cos / r^2 = %.5f" % (direct, expected))
