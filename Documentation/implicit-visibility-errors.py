"""Where implied visibility goes wrong: per-vertex error maps of the implicit-visibility
method (vtkGlobalIlluminationFilter, Method IMPLICIT_VISIBILITY) against the link method with
1024 rays per vertex and no smoothing (the reference stand-in: 1.5% from the path tracer on
the Cornell box). The colour is the signed error of the indirect irradiance (luminance) in
units of its scene mean, from -50% (blue) to +50% (red).

Panels: the Cornell box (its point light; contacts of the blocks with the floor and walls)
at N = 8 and N = 16 bins per face side, and a thin plate of few vertices (a box 2 x 0.02 x 2
of 24 vertices, four per face) 0.5 above a floor under a white sky, at N = 16.

Usage (from the repository root, after building build-iv):
  PYTHONPATH=build-iv/lib/python3.11/dist-packages Testing/run_with_xvfb.sh \\
    /usr/bin/python3 Documentation/implicit-visibility-errors.py Documentation/implicit-visibility-errors.png
"""
import sys

import linkgi
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkFiltersCore import vtkAppendPolyData, vtkTriangleFilter
from vtkmodules.vtkFiltersSources import vtkCubeSource, vtkPlaneSource
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingCore import (vtkActor, vtkColorTransferFunction, vtkLightCollection,
                                         vtkPolyDataMapper,
                                         vtkRenderer, vtkRenderWindow, vtkTextActor,
                                         vtkWindowToImageFilter)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401
import vtkmodules.vtkRenderingFreeType  # noqa: F401

LUMA = (0.2126, 0.7152, 0.0722)


def solve(source, lights, method, bins=16, rays=1024, sky=(0, 0, 0)):
    gi = linkgi.vtkGlobalIlluminationFilter()
    gi.SetInputConnection(source.GetOutputPort())
    for light in lights:
        gi.AddLight(light)
    gi.SetBackendToCPU()
    gi.SetEnvironmentColor(*sky)
    if hasattr(source, "GetSceneName"):
        gi.SetAlbedoArrayName("Albedo")
        gi.SetEmissionArrayName("Emission")
    if method == "links":
        gi.SetMethodToLinks()
        gi.SetRaysPerVertex(rays)
        gi.SetSmoothing(False)
    else:
        gi.SetMethodToImplicitVisibility()
        gi.SetImplicitVisibilityBins(bins)
    gi.Update()
    out = gi.GetOutput()
    indirect = vtk_to_numpy(out.GetPointData().GetArray("IndirectIrradiance"))
    return out, indirect @ LUMA


def error_map(source, lights, bins, sky=(0, 0, 0)):
    ref_out, ref = solve(source, lights, "links", sky=sky)
    out, iv = solve(source, lights, "iv", bins=bins, sky=sky)
    err = (iv - ref) / max(ref.mean(), 1e-12)
    out.GetPointData().SetScalars(numpy_to_vtk(err.astype("float32"), deep=True))
    rms = float((err ** 2).mean() ** 0.5)
    return out, rms


def panel(window, viewport, poly, title, camera, outline=None):
    ctf = vtkColorTransferFunction()
    ctf.AddRGBPoint(-0.5, 0.15, 0.3, 0.9)
    ctf.AddRGBPoint(0.0, 0.97, 0.97, 0.97)
    ctf.AddRGBPoint(0.5, 0.9, 0.15, 0.1)
    mapper = vtkPolyDataMapper()
    mapper.SetInputData(poly)
    mapper.SetLookupTable(ctf)
    mapper.SetScalarRange(-0.5, 0.5)
    mapper.SetScalarModeToUsePointData()
    mapper.InterpolateScalarsBeforeMappingOn()
    actor = vtkActor()
    actor.SetMapper(mapper)
    actor.GetProperty().LightingOff()
    renderer = vtkRenderer()
    renderer.SetViewport(*viewport)
    renderer.SetBackground(0.2, 0.2, 0.22)
    renderer.AddActor(actor)
    if outline is not None:
        edges = vtkPolyDataMapper()
        edges.SetInputData(outline)
        edges.ScalarVisibilityOff()
        frame = vtkActor()
        frame.SetMapper(edges)
        frame.GetProperty().SetRepresentationToWireframe()
        frame.GetProperty().SetColor(0.1, 0.1, 0.1)
        frame.GetProperty().SetLineWidth(2)
        renderer.AddActor(frame)
    text = vtkTextActor()
    text.SetInput(title)
    text.GetTextProperty().SetFontSize(16)
    text.GetTextProperty().SetColor(0.05, 0.05, 0.05)
    text.GetTextProperty().SetBackgroundColor(1, 1, 1)
    text.GetTextProperty().SetBackgroundOpacity(0.8)
    text.SetPosition(8, 8)
    renderer.AddViewProp(text)
    window.AddRenderer(renderer)
    renderer.ResetCamera()
    cam = renderer.GetActiveCamera()
    camera(cam)
    renderer.ResetCameraClippingRange()


def main(path):
    cornell = linkgi.vtkGlobalIlluminationSceneSource()
    cornell.SetSceneName("cornell")
    cornell.Update()
    collection = vtkLightCollection()
    cornell.CreateLights(collection)
    lights = [collection.GetItemAsObject(i) for i in range(collection.GetNumberOfItems())]
    c8, rms8 = error_map(cornell, lights, 8)
    c16, rms16 = error_map(cornell, lights, 16)

    floor = vtkPlaneSource()
    floor.SetOrigin(-2, 0, -2)
    floor.SetPoint1(-2, 0, 2)
    floor.SetPoint2(2, 0, -2)
    floor.SetResolution(40, 40)
    plate = vtkCubeSource()
    plate.SetCenter(0, 0.5, 0)
    plate.SetXLength(2)
    plate.SetYLength(0.02)
    plate.SetZLength(2)
    scene = vtkAppendPolyData()
    scene.AddInputConnection(floor.GetOutputPort())
    scene.AddInputConnection(plate.GetOutputPort())
    tris = vtkTriangleFilter()
    tris.SetInputConnection(scene.GetOutputPort())
    p16, rmsp = error_map(tris, [], 16, sky=(1, 1, 1))
    # The floor alone (its points come first in the appended mesh), the plate as an outline.
    floor.Update()
    floor_errors = vtkPolyData()
    floor_errors.DeepCopy(floor.GetOutput())
    errors = vtk_to_numpy(p16.GetPointData().GetScalars())[:floor_errors.GetNumberOfPoints()]
    floor_errors.GetPointData().SetScalars(numpy_to_vtk(errors.copy(), deep=True))
    plate.Update()

    bounds = c16.GetBounds()
    center = [(bounds[0] + bounds[1]) / 2, (bounds[2] + bounds[3]) / 2, (bounds[4] + bounds[5]) / 2]

    def front(cam):
        cam.SetFocalPoint(*center)
        cam.SetPosition(center[0], center[1], center[2] - 2.4 * (bounds[5] - bounds[4]))
        cam.SetViewUp(0, 1, 0)

    def above(cam):
        cam.SetFocalPoint(0, 0, 0)
        cam.SetPosition(0, 5.5, 2.5)
        cam.SetViewUp(0, 1, 0)

    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(1500, 520)
    panel(window, (0, 0, 1 / 3, 1), c8, "Cornell, N = 8 (RMS %.0f%%)" % (100 * rms8), front)
    panel(window, (1 / 3, 0, 2 / 3, 1), c16, "Cornell, N = 16 (RMS %.0f%%)" % (100 * rms16), front)
    panel(window, (2 / 3, 0, 1, 1), floor_errors,
          "floor under a 24-vertex plate, sky, N = 16 (RMS %.0f%%)" % (100 * rmsp), above,
          outline=plate.GetOutput())
    window.Render()
    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.Update()
    writer = vtkPNGWriter()
    writer.SetFileName(path)
    writer.SetInputConnection(grab.GetOutputPort())
    writer.Write()
    print("cornell N=8 rms %.3f, N=16 rms %.3f, plate N=16 rms %.3f" % (rms8, rms16, rmsp))


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "implicit-visibility-errors.png")
