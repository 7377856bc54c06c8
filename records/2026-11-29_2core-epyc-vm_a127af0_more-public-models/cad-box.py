"""A CAD-like box standing on a floor: the floor is 8 large triangles that share the box's
four base corners, the box has no bottom. Writes OUT.vtp without normals (the filter
computes them, split at the box's edges), OUT-split.vtp with normals split at its edges and
OUT-smooth.vtp with one normal per point averaged over its faces, as CAD exports write them.

    PYTHONPATH=build/lib/python3.11/dist-packages /usr/bin/python3 cad-box.py OUT
"""
import sys

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
from vtkmodules.vtkFiltersCore import vtkPolyDataNormals
from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter

OUTER = [(-50, -50), (50, -50), (50, 50), (-50, 50)]
INNER = [(-10, -2), (10, -2), (10, 0), (-10, 0)]  # the box's footprint, counter-clockwise
HEIGHT = 15.0


def box_on_floor():
    points = [(x, y, 0.0) for x, y in OUTER] + [(x, y, 0.0) for x, y in INNER] + [(x, y, HEIGHT) for x, y in INNER]
    triangles = []
    for k in range(4):  # the floor between the outer square and the footprint, facing +z
        a, b, ia, ib = k, (k + 1) % 4, 4 + k, 4 + (k + 1) % 4
        triangles += [(a, b, ib), (a, ib, ia)]
    for k in range(4):  # the box's sides, facing outward
        a, b = 4 + k, 4 + (k + 1) % 4
        triangles += [(a, b, b + 4), (a, b + 4, a + 4)]
    triangles += [(8, 9, 10), (8, 10, 11)]  # its top, facing +z
    surface = vtkPolyData()
    positions = vtkPoints()
    positions.SetData(numpy_to_vtk(np.array(points, dtype=float)))
    surface.SetPoints(positions)
    cells = vtkCellArray()
    for t in triangles:
        cells.InsertNextCell(3, t)
    surface.SetPolys(cells)
    return surface


def write(surface, path):
    writer = vtkXMLPolyDataWriter()
    writer.SetFileName(path)
    writer.SetInputData(surface)
    writer.Write()


def with_normals(surface, split):
    normals = vtkPolyDataNormals()
    normals.SetInputData(surface)
    normals.SetSplitting(split)
    normals.SetFeatureAngle(30)
    normals.Update()
    return normals.GetOutput()


if __name__ == "__main__":
    box = box_on_floor()
    write(box, sys.argv[1] + ".vtp")
    write(with_normals(box, True), sys.argv[1] + "-split.vtp")
    write(with_normals(box, False), sys.argv[1] + "-smooth.vtp")
