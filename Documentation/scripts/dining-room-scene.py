"""The dining room ('The Breakfast Room' by Wig42, in Benedikt Bitterli's rendering
resources) as one vtkPolyData for the filter: every shape of the Mitsuba scene file merged,
each with the diffuse albedo its material gives (a point array `Albedo`, linear RGB), in
metres, decimated to about the points asked for.

    PYTHONPATH=build/lib/python3.11/dist-packages /usr/bin/python3 \\
      Documentation/scripts/dining-room-scene.py DIR OUT.vtp [POINTS]

DIR holds the scene as Bitterli's Mitsuba download has it (scene.xml, models/, textures/),
for example `dining-room/` of github.com/jgarciapueyo/mitsuba2-transient-scenes at
ab67c4caa9228aa9d4115aeb90c3d3bab0aaf7b5 (CC BY 3.0, LICENSE.txt there). POINTS (default
24000) is the size asked before large faces are split (the output has about 32,000).

Materials: `diffuse` gives its reflectance, `roughplastic` its diffuse reflectance, a
bitmap the mean of its texels decoded from sRGB, conductors (chrome, gold, metal: no
diffuse part) 0.5. Mitsuba's `twosided` is dropped: the filter lights the side a surface's
winding faces, as the file gives it. Every triangle is split until its edges are at most 20 cm
(vtkAdaptiveSubdivisionFilter), so that large faces (the room, the table top) are lit per
vertex: the reference lights the point its paths hit, the methods interpolate the vertices.
Besides the room (walls, floor, ceiling, skirting), every part is first decimated
(vtkQuadricDecimation) by one factor
(to 400 triangles at least), parts under 1100 triangles kept whole (decimated, the
double walls of a lamp shade cross each other and shadow its inside).
The scene's unit is 1/3 m (its table stands 0.78 m high).
"""
import os
import sys
import xml.etree.ElementTree as ET

from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
from vtkmodules.vtkCommonTransforms import vtkTransform
from vtkmodules.vtkFiltersCore import (vtkAppendPolyData, vtkCleanPolyData, vtkQuadricDecimation,
                                        vtkTriangleFilter)
from vtkmodules.vtkFiltersGeneral import vtkTransformPolyDataFilter
from vtkmodules.vtkFiltersModeling import vtkAdaptiveSubdivisionFilter
from vtkmodules.vtkIOGeometry import vtkOBJReader
from vtkmodules.vtkIOImage import vtkJPEGReader, vtkPNGReader
from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter
import numpy as np

METRES_PER_UNIT = 1.0 / 3.0
ROOM_EDGE = 0.20  # metres
KEEP_BELOW = 1100  # triangles: parts this small are kept whole
DECIMATE_TO = 400  # triangles at least, for the others


def srgb_to_linear(c):
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def texture_mean(path):
    reader = vtkPNGReader() if path.lower().endswith(".png") else vtkJPEGReader()
    reader.SetFileName(path)
    reader.Update()
    texels = vtk_to_numpy(reader.GetOutput().GetPointData().GetScalars()).astype(float) / 255.0
    return srgb_to_linear(texels[:, :3]).mean(axis=0)


def rgb(text):
    values = [float(v) for v in text.replace(",", " ").split()]
    return np.array(values * 3 if len(values) == 1 else values[:3])


def albedo_of(bsdf, folder):
    """The diffuse albedo of a Mitsuba 0.5 bsdf element (twosided unwrapped)."""
    while bsdf.get("type") == "twosided":
        bsdf = bsdf.find("bsdf")
    kind = bsdf.get("type")
    name = {"diffuse": "reflectance", "roughdiffuse": "reflectance", "plastic": "diffuseReflectance",
            "roughplastic": "diffuseReflectance"}.get(kind)
    if name is None:
        return np.array([0.5, 0.5, 0.5]), kind  # a conductor: no diffuse part
    for child in bsdf:
        if child.get("name") != name:
            continue
        if child.tag == "texture":
            return texture_mean(os.path.join(folder, child.find("string").get("value"))), kind + " (texture)"
        return rgb(child.get("value")), kind
    return np.array([0.5, 0.5, 0.5]), kind


def to_world(shape):
    transform = vtkTransform()
    matrix = shape.find("transform/matrix")
    if matrix is not None:
        transform.SetMatrix([float(v) for v in matrix.get("value").split()])
    scale = vtkTransform()
    scale.Scale(METRES_PER_UNIT, METRES_PER_UNIT, METRES_PER_UNIT)
    scale.Concatenate(transform)
    return scale


def rectangle():
    """Mitsuba's rectangle: [-1, 1]^2 at z = 0, facing +z."""
    poly = vtkPolyData()
    points = vtkPoints()
    for x, y in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
        points.InsertNextPoint(x, y, 0)
    cells = vtkCellArray()
    cells.InsertNextCell(3, [0, 1, 2])
    cells.InsertNextCell(3, [0, 2, 3])
    poly.SetPoints(points)
    poly.SetPolys(cells)
    return poly


def bare_triangles(poly):
    """Triangles alone, seams of the OBJ's texture coordinates and normals merged."""
    bare = vtkPolyData()
    bare.SetPoints(poly.GetPoints())
    bare.SetPolys(poly.GetPolys())
    triangles = vtkTriangleFilter()
    triangles.SetInputData(bare)
    clean = vtkCleanPolyData()
    clean.SetInputConnection(triangles.GetOutputPort())
    clean.PointMergingOn()
    clean.SetTolerance(0.0)
    clean.Update()
    return clean.GetOutput()


def read_parts(folder):
    """(name, surface in metres, albedo, material) for every shape of scene.xml."""
    root = ET.parse(os.path.join(folder, "scene.xml")).getroot()
    materials = {b.get("id"): b for b in root.findall("bsdf")}
    for shape in root.findall("shape"):
        if shape.get("type") == "obj":
            name = shape.find("string[@name='filename']").get("value")
            reader = vtkOBJReader()
            reader.SetFileName(os.path.join(folder, name))
            reader.Update()
            surface = reader.GetOutput()
        elif shape.get("type") == "rectangle":
            name, surface = "rectangle", rectangle()
        else:
            raise SystemExit("unknown shape " + shape.get("type"))
        move = vtkTransformPolyDataFilter()
        move.SetTransform(to_world(shape))
        move.SetInputData(bare_triangles(surface))
        move.Update()
        material = shape.find("ref").get("id")
        albedo, kind = albedo_of(materials[material], folder)
        yield name, move.GetOutput(), albedo, material + " " + kind


def is_room(name, material):
    return material.split()[0] in ("Walls", "FloorTiles", "SkirtWood") or name == "rectangle"


def subdivided(surface, edge):
    split = vtkAdaptiveSubdivisionFilter()
    split.SetInputData(surface)
    split.SetMaximumEdgeLength(edge)
    split.Update()
    return bare_triangles(split.GetOutput())


def decimated(surface, keep):
    if surface.GetNumberOfPolys() < KEEP_BELOW or keep >= 1.0:
        return surface
    target = max(DECIMATE_TO, int(surface.GetNumberOfPolys() * keep))
    decimate = vtkQuadricDecimation()
    decimate.SetInputData(surface)
    decimate.SetTargetReduction(1.0 - target / surface.GetNumberOfPolys())
    decimate.VolumePreservationOn()
    decimate.Update()
    return bare_triangles(decimate.GetOutput())


def with_arrays(surface, albedo, part):
    """The part's albedo, and its index in scene.xml's order (`Part`) to find it again."""
    n = surface.GetNumberOfPoints()
    for name, values in (("Albedo", np.tile(albedo.astype(np.float32), (n, 1))),
                         ("Part", np.full(n, part, dtype=np.int32))):
        array = numpy_to_vtk(values, deep=1)
        array.SetName(name)
        surface.GetPointData().AddArray(array)
    return surface


def main(folder, out, points):
    parts = list(read_parts(folder))
    room = [(i, n, subdivided(s, ROOM_EDGE), a, m) for i, (n, s, a, m) in enumerate(parts) if is_room(n, m)]
    rest = [(i,) + p for i, p in enumerate(parts) if not is_room(p[0], p[3])]
    room_points = sum(p[2].GetNumberOfPoints() for p in room)
    rest_points = sum(p[2].GetNumberOfPoints() for p in rest)
    whole = sum(p[2].GetNumberOfPoints() for p in rest if p[2].GetNumberOfPolys() < KEEP_BELOW)
    keep = max(0.0, points - room_points - whole) / (rest_points - whole)
    append = vtkAppendPolyData()
    rest = [(i, n, subdivided(decimated(s, keep), ROOM_EDGE), a, m) for i, n, s, a, m in rest]
    for i, name, surface, albedo, material in room + rest:
        print("%2d %-18s %-40s albedo %.3f %.3f %.3f: %6d points, %6d triangles (of %d)"
              % (i, name, material, *albedo, surface.GetNumberOfPoints(), surface.GetNumberOfPolys(),
                 parts[i][1].GetNumberOfPolys()))
        append.AddInputData(with_arrays(surface, albedo, i))
    append.Update()
    scene = append.GetOutput()
    b = scene.GetBounds()
    print("%d points, %d triangles; %.2f x %.2f x %.2f m" % (scene.GetNumberOfPoints(), scene.GetNumberOfPolys(),
                                                           b[1] - b[0], b[3] - b[2], b[5] - b[4]))
    writer = vtkXMLPolyDataWriter()
    writer.SetFileName(out)
    writer.SetInputData(scene)
    writer.SetDataModeToAppended()
    writer.SetCompressorTypeToZLib()
    writer.Write()


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2], int(sys.argv[3]) if len(sys.argv) > 3 else 24000)
