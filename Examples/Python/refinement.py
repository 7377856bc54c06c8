"""Adaptive refinement: a floor of two triangles and a box of twelve under a point light,
lit per point without and with vtkGlobalIlluminationFilter's Refinement, side by side
(per-point radiance, flat interpolation between points, the mesh's edges drawn over it).
Usage: /usr/bin/python3 refinement.py out.png        (LinkGI installed; or with
       PYTHONPATH=build/lib/python3.11/dist-packages, under Xvfb without a display)"""
import sys
import linkgi
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkFiltersCore import vtkAppendPolyData, vtkTriangleFilter
from vtkmodules.vtkFiltersSources import vtkCubeSource, vtkPlaneSource
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingCore import (vtkActor, vtkLight, vtkPolyDataMapper, vtkRenderer,
                                         vtkRenderWindow, vtkWindowToImageFilter)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (the OpenGL object factory)
import numpy

floor = vtkPlaneSource()  # 4 x 4, facing +z: two triangles
floor.SetOrigin(-2, -2, 0)
floor.SetPoint1(2, -2, 0)
floor.SetPoint2(-2, 2, 0)
box = vtkCubeSource()  # 1 x 1 x 1 on the floor: twelve triangles
box.SetCenter(0.3, 0.2, 0.5)
scene = vtkAppendPolyData()
scene.AddInputConnection(floor.GetOutputPort())
scene.AddInputConnection(box.GetOutputPort())
triangles = vtkTriangleFilter()
triangles.SetInputConnection(scene.GetOutputPort())

light = vtkLight()
light.SetPositional(True)
light.SetAttenuationValues(0, 0, 1)  # a lamp: 1/r^2 (VTK's default does not fall off)
light.SetConeAngle(90)
light.SetPosition(-1.2, -0.8, 2.2)
light.SetIntensity(6)


def lit(refine):
    gi = linkgi.vtkGlobalIlluminationFilter()
    gi.SetInputConnection(triangles.GetOutputPort())
    gi.AddLight(light)
    gi.SetEnvironmentColor(0.03, 0.03, 0.04)
    gi.SetRefinement(refine)
    gi.SetRefinementMaxVertices(12000)
    gi.SetRefinementRounds(7)
    gi.Update()
    out = gi.GetOutput()
    # Radiance (linear RGB) to 8-bit sRGB-ish colours: exposure, clamp, gamma 1/2.2.
    radiance = vtk_to_numpy(out.GetPointData().GetArray("Radiance"))
    rgb = numpy.clip(radiance * 2.0, 0.0, 1.0) ** (1.0 / 2.2)
    colours = numpy_to_vtk((rgb * 255).astype(numpy.uint8), deep=True)
    colours.SetName("Colours")
    out.GetPointData().SetScalars(colours)
    return out


window = vtkRenderWindow()
window.SetSize(1200, 560)
window.SetOffScreenRendering(1)
for i, refine in enumerate((0, 1)):
    data = lit(refine)
    renderer = vtkRenderer()
    renderer.SetViewport(0.5 * i, 0.0, 0.5 * (i + 1), 1.0)
    renderer.SetBackground(1, 1, 1)
    for wire in (False, True):
        mapper = vtkPolyDataMapper()
        mapper.SetInputData(data)
        mapper.SetColorModeToDirectScalars()
        mapper.SetScalarVisibility(not wire)
        if not wire:  # push the surface back so that its edges are drawn over it
            mapper.SetResolveCoincidentTopologyToPolygonOffset()
            mapper.SetRelativeCoincidentTopologyPolygonOffsetParameters(4, 4)
        actor = vtkActor()
        actor.SetMapper(mapper)
        prop = actor.GetProperty()
        prop.SetLighting(False)  # the colours are the light
        if wire:
            prop.SetRepresentationToWireframe()
            prop.SetColor(0.2, 0.2, 0.2)
            prop.SetOpacity(0.35)
        renderer.AddActor(actor)
    camera = renderer.GetActiveCamera()
    camera.SetPosition(2.6, -4.2, 3.4)
    camera.SetFocalPoint(0.0, 0.0, 0.3)
    camera.SetViewUp(0, 0, 1)
    renderer.ResetCameraClippingRange()
    window.AddRenderer(renderer)
    print("%s: %d points" % ("refined" if refine else "input", data.GetNumberOfPoints()))
window.Render()
grab = vtkWindowToImageFilter()
grab.SetInput(window)
writer = vtkPNGWriter()
writer.SetInputConnection(grab.GetOutputPort())
writer.SetFileName(sys.argv[1] if len(sys.argv) > 1 else "refinement.png")
writer.Write()
sys.exit(0 if writer.GetErrorCode() == 0 else 1)
