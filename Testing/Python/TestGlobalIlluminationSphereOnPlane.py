"""vtkGlobalIlluminationFilter from Python: a sphere floating just above a floor under a
point light casts a shadow, the floor under it still gets bounced light, the arrays
survive a round trip through a .vtp file, the floor and the sphere as two blocks of a
vtkMultiBlockDataSet are the same scene, and the reference path tracer finds the floor's
shadow and bounced light too.

Usage: TestGlobalIlluminationSphereOnPlane.py <output directory>
"""
import math
import os
import sys

import linkgi
from vtkmodules.vtkCommonDataModel import vtkMultiBlockDataSet, vtkPolyData
from vtkmodules.vtkFiltersCore import vtkAppendPolyData
from vtkmodules.vtkFiltersSources import vtkPlaneSource, vtkSphereSource
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader, vtkXMLPolyDataWriter
from vtkmodules.vtkRenderingCore import vtkLight

ARRAYS = ("DirectIrradiance", "IndirectIrradiance", "Radiance")


def sphere_over_floor():
    floor = vtkPlaneSource()  # 4 x 4 at z = 0, facing +z
    floor.SetOrigin(-2, -2, 0)
    floor.SetPoint1(2, -2, 0)
    floor.SetPoint2(-2, 2, 0)
    floor.SetResolution(40, 40)
    sphere = vtkSphereSource()  # radius 0.5, 0.1 above the floor
    sphere.SetCenter(0, 0, 0.6)
    sphere.SetRadius(0.5)
    sphere.SetThetaResolution(32)
    sphere.SetPhiResolution(16)
    append = vtkAppendPolyData()
    append.AddInputConnection(floor.GetOutputPort())  # floor points first
    append.AddInputConnection(sphere.GetOutputPort())
    append.Update()
    return append.GetOutput(), floor.GetOutput().GetNumberOfPoints(), append


def check_reference(scene, light, floor_points):
    """SetMethodToReference from Python: the path tracer's direct light equals the links'
    (both exact, one shadow ray per vertex) and the links' mean indirect light on the floor
    is within 10% of it."""
    gi = linkgi.vtkGlobalIlluminationFilter()
    gi.SetInputData(scene)
    gi.SetLightOversampling(False)
    gi.AddLight(light)
    gi.Update()
    links = vtkPolyData()
    links.DeepCopy(gi.GetOutput())
    gi.SetMethodToReference()
    gi.SetReferencePathsPerVertex(256)
    gi.Update()
    out = gi.GetOutput()
    assert gi.GetMethodAsString() == "reference"
    assert out.GetFieldData().GetAbstractArray("LinkGI.Method").GetValue(0) == "reference"
    assert out.GetFieldData().GetArray("LinkGI.Paths").GetValue(0) == 256 * scene.GetNumberOfPoints()

    def mean(data, name, first=0, last=None):
        a = data.GetPointData().GetArray(name)
        last = a.GetNumberOfTuples() if last is None else last
        return sum(a.GetComponent(i, 0) for i in range(first, last)) / (last - first)

    ratio = mean(links, "IndirectIrradiance", 0, floor_points) / mean(out, "IndirectIrradiance", 0, floor_points)
    print(f"reference: the links' indirect light on the floor / the reference's {ratio:.3f}")
    assert abs(mean(out, "DirectIrradiance") / mean(links, "DirectIrradiance") - 1) < 1e-4
    assert abs(ratio - 1) < 0.10


def check_blocks(append, light, appended):
    """The inputs of `append` as two blocks give the appended surface's arrays."""
    blocks = vtkMultiBlockDataSet()
    for i in range(2):
        blocks.SetBlock(i, append.GetInputDataObject(0, i))
    gi = linkgi.vtkGlobalIlluminationFilter()
    gi.SetInputData(blocks)
    gi.SetRaysPerVertex(64)
    gi.AddLight(light)
    gi.Update()
    out = gi.GetOutputDataObject(0)
    assert out.IsA("vtkMultiBlockDataSet") and out.GetNumberOfBlocks() == 2
    first = 0
    for i in range(2):
        block = out.GetBlock(i)
        for name in ARRAYS:
            a, b = block.GetPointData().GetArray(name), appended.GetPointData().GetArray(name)
            assert a.GetNumberOfTuples() == block.GetNumberOfPoints(), name
            assert all(math.isclose(a.GetValue(k), b.GetValue(3 * first + k), abs_tol=1e-6)
                       for k in range(a.GetNumberOfValues())), name
        first += block.GetNumberOfPoints()
    assert first == appended.GetNumberOfPoints()


def nearest(polydata, count, target):
    """Id of the point among the first `count` that is closest to `target`."""
    def dist2(i):
        return sum((a - b) ** 2 for a, b in zip(polydata.GetPoint(i), target))
    return min(range(count), key=dist2)


def main(outdir):
    scene, floor_points, append = sphere_over_floor()
    light = vtkLight()  # a point light of 16 W/sr 4 m above the floor: E = 1 below it
    light.SetPositional(True)
    light.SetAttenuationValues(0, 0, 1)  # a lamp: 1/r^2 (VTK's default does not fall off)
    light.SetConeAngle(90)
    light.SetPosition(0, 0, 4)
    light.SetFocalPoint(0, 0, 0)
    light.SetIntensity(16)

    gi = linkgi.vtkGlobalIlluminationFilter()
    gi.SetInputData(scene)
    gi.SetRaysPerVertex(64)
    gi.AddLight(light)
    gi.Update()
    out = gi.GetOutput()
    pd = out.GetPointData()
    for name in ARRAYS:
        array = pd.GetArray(name)
        assert array is not None, name
        assert array.GetNumberOfTuples() == scene.GetNumberOfPoints(), name
        assert array.GetNumberOfComponents() == 3, name

    under = nearest(out, floor_points, (0, 0, 0))
    away = nearest(out, floor_points, (1.5, 1.5, 0))
    direct_under = pd.GetArray("DirectIrradiance").GetComponent(under, 0)
    direct_away = pd.GetArray("DirectIrradiance").GetComponent(away, 0)
    indirect_under = pd.GetArray("IndirectIrradiance").GetComponent(under, 0)
    r2 = 1.5 ** 2 * 2 + 16
    expected_away = 16 * 4 / r2 ** 1.5  # I cos(theta) / r^2
    print(f"direct under the sphere {direct_under:.4f}, away {direct_away:.4f} "
          f"(expected {expected_away:.4f}); indirect under the sphere {indirect_under:.4f}")
    assert direct_under < 0.01, "the sphere must cast a shadow"
    assert math.isclose(direct_away, expected_away, rel_tol=1e-3)
    assert indirect_under > 0.0, "light bounced off the sphere's underside reaches the floor"

    filename = os.path.join(outdir, "GlobalIlluminationSphereOnPlane.vtp")
    writer = vtkXMLPolyDataWriter()
    writer.SetInputData(out)
    writer.SetFileName(filename)
    assert writer.Write() == 1
    reader = vtkXMLPolyDataReader()
    reader.SetFileName(filename)
    reader.Update()
    back = reader.GetOutput()
    for name in ARRAYS:
        a, b = pd.GetArray(name), back.GetPointData().GetArray(name)
        assert b is not None, f"{name} lost in the .vtp file"
        assert b.GetNumberOfTuples() == a.GetNumberOfTuples()
        assert all(a.GetValue(i) == b.GetValue(i) for i in range(a.GetNumberOfValues())), name
    elements = back.GetFieldData().GetArray("LinkGI.Elements")
    assert elements is not None and elements.GetValue(0) == scene.GetNumberOfPoints()
    check_blocks(append, light, out)
    check_reference(scene, light, floor_points)
    assert linkgi.vtkGlobalIlluminationAsyncWatcher().GetInterval() == 30
    print("ok")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else ".")
