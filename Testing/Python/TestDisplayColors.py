"""vtkGlobalIlluminationDisplayColors bakes what the mapper displays: the baked colours,
drawn unlit by VTK at the same camera, match the global illumination mapper's picture
(mean CIEDE2000 over the covered pixels <= 2, the difference being the mapper's per-pixel
shadows and direct light against per-vertex ones) in a lamp scene (automatic exposure,
exponential curve) and a colour-mapped scene under a directional light (hue-preserving
display); and the light terms add up: direct and indirect differ from combined where there
is bounced light. The same holds where a surface's normals point against its winding (the
mapper lights the side the normals point to, as the filter does). Colours by cell give every cell points of its own with its colour (a
plane under a directional light of intensity 1 shows the lookup table's colours exactly).

Usage: TestDisplayColors.py [output directory for the images]
"""
import os
import sys

import numpy as np

import linkgi
import linkgi_export_testing as testing


def check(name, window, out):
    scene = linkgi.bake(window)
    mapper_image = testing.grab(window)
    baked_image = testing.grab(testing.baked_window(scene, "combined"))
    testing.write_png(mapper_image, os.path.join(out, f"DisplayColors-{name}-mapper.png"))
    testing.write_png(baked_image, os.path.join(out, f"DisplayColors-{name}-baked.png"))
    background = tuple(int(round(255 * c)) for c in scene.background)
    difference, covered = testing.mean_difference(mapper_image, baked_image, background)
    print(f"{name}: mean CIEDE2000 {difference:.2f} over {covered} pixels")
    assert covered > 0.3 * mapper_image.shape[0] * mapper_image.shape[1], covered
    assert difference <= 2.0, f"{name}: baked colours differ from the mapper's: {difference:.2f}"
    part = scene.parts[0]
    combined = part.colors["combined"].astype(int)
    direct = part.colors["direct"].astype(int)
    indirect = part.colors["indirect"].astype(int)
    # Bounced light brightens: combined is never darker than direct, and brighter somewhere.
    assert (combined >= direct - 1).all(), f"{name}: combined darker than direct"
    assert (combined.sum(axis=1) > direct.sum(axis=1) + 3).any(), f"{name}: no bounced light"
    assert indirect.max() > 0 and (indirect.sum(axis=1) < combined.sum(axis=1)).any()
    return scene


def check_cell_colours():
    """Colours by cell: every cell gets points of its own carrying its colour. A plane facing
    a directional light of intensity 1, nothing to bounce off (black sky): irradiance 1
    everywhere, so the calibrated display shows each cell's lookup-table colour exactly."""
    from vtkmodules.vtkCommonCore import vtkIntArray, vtkLookupTable
    from vtkmodules.vtkFiltersSources import vtkPlaneSource
    from vtkmodules.vtkRenderingCore import vtkLight, vtkLightCollection, vtkPolyDataMapper, vtkProperty
    from vtkmodules.util.numpy_support import vtk_to_numpy

    plane = vtkPlaneSource()
    plane.SetResolution(3, 2)
    plane.Update()
    surface = plane.GetOutput()
    index = vtkIntArray()
    index.SetName("index")
    for i in range(surface.GetNumberOfCells()):
        index.InsertNextValue(i)
    surface.GetCellData().AddArray(index)
    sun = vtkLight()
    sun.SetPosition(0, 0, 1)
    sun.SetFocalPoint(0, 0, 0)
    gi = linkgi.vtkGlobalIlluminationFilter()
    gi.SetInputData(surface)
    gi.AddLight(sun)
    gi.Update()
    table = vtkLookupTable()
    table.SetNumberOfTableValues(surface.GetNumberOfCells())
    table.SetRange(0, surface.GetNumberOfCells() - 1)
    table.Build()
    mapper = vtkPolyDataMapper()
    mapper.SetLookupTable(table)
    mapper.SetScalarModeToUseCellFieldData()
    mapper.SelectColorArray("index")
    mapper.SetScalarRange(0, surface.GetNumberOfCells() - 1)
    lights = vtkLightCollection()
    lights.AddItem(sun)
    colors = linkgi.vtkGlobalIlluminationDisplayColors()
    colors.SetInputConnection(gi.GetOutputPort())
    colors.SetMapper(mapper)
    colors.SetProperty(vtkProperty())
    colors.SetLights(lights)
    colors.Update()
    baked = colors.GetOutput()
    cells = surface.GetNumberOfCells()
    assert baked.GetNumberOfPoints() == 4 * cells, baked.GetNumberOfPoints()
    shown = vtk_to_numpy(baked.GetPointData().GetArray("DisplayColors"))
    rgb = [0.0, 0.0, 0.0]
    for cell in range(cells):
        ids = baked.GetCell(cell).GetPointIds()
        table.GetColor(cell, rgb)
        expected = np.round(255 * np.array(rgb))
        for k in range(ids.GetNumberOfIds()):
            got = shown[ids.GetId(k)]
            assert np.abs(got - expected).max() <= 1, (cell, got, expected)
    print(f"colours by cell: {cells} cells on points of their own, each its table colour")


out = testing.output_dir(sys.argv)
check_cell_colours()
lamp = check("lamp", testing.lamp_scene(), out)
assert lamp.parts and lamp.mode == "combined"
check("colour-map", testing.colour_map_scene(), out)
# Normals against the winding: the mapper lights the side the normals point to, as the filter
# does (VTK's own two-sided lighting would draw the plane dark).
check("against-winding", testing.lamp_scene(against_winding=True), out)
print("ok")
