"""The caustic scene lit by photon mapping: a glass ball and a mirror band over a white floor
under a point light (vtkGlobalIlluminationSceneSource "caustics", its Material and
IndexOfRefraction cell arrays). Three panels of the floor seen from above at an angle, each
the luminance of one point array on a log scale from 1e-3 to 10 W/m^2 (black to white):
DirectIrradiance (the ball's shadow), IndirectIrradiance without the caustics (light bounced
off the floor and the band), CausticIrradiance (the ball's focus and the band's ring).

Usage (from the repository root, after building build/):
  PYTHONPATH=build/lib/python3.11/dist-packages Testing/run_with_xvfb.sh \\
    /usr/bin/python3 Documentation/caustics-images.py Documentation/caustics.png
"""
import math
import sys

import linkgi
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingCore import (vtkActor, vtkColorTransferFunction, vtkLightCollection,
                                         vtkPolyDataMapper, vtkRenderer, vtkRenderWindow,
                                         vtkTextActor, vtkWindowToImageFilter)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401
import vtkmodules.vtkRenderingFreeType  # noqa: F401

LUMA = (0.2126, 0.7152, 0.0722)


def main(path):
    source = linkgi.vtkGlobalIlluminationSceneSource()
    source.SetSceneName("caustics")
    lights = vtkLightCollection()
    source.CreateLights(lights)
    gi = linkgi.vtkGlobalIlluminationFilter()
    gi.SetInputConnection(source.GetOutputPort())
    lights.InitTraversal()
    for _ in range(lights.GetNumberOfItems()):
        gi.AddLight(lights.GetNextItem())
    gi.SetAlbedoArrayName("Albedo")
    gi.SetMaterialArrayName("Material")
    gi.SetIndexOfRefractionArrayName("IndexOfRefraction")
    gi.SetMethodToPhotonMapping()
    gi.SetNumberOfPhotons(1048576)
    gi.SetBackendToCPU()
    gi.Update()
    lit = gi.GetOutput()

    def luminance(name):
        return vtk_to_numpy(lit.GetPointData().GetArray(name)) @ LUMA

    caustics = luminance("CausticIrradiance")
    panels = [("Direct", luminance("DirectIrradiance")),
              ("Indirect without caustics", luminance("IndirectIrradiance") - caustics),
              ("Caustics", caustics)]
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(1200, 420)
    lut = vtkColorTransferFunction()
    for log10, grey in ((-3.0, 0.0), (1.0, 1.0)):
        lut.AddRGBPoint(log10, grey, grey, grey)
    for i, (title, values) in enumerate(panels):
        surface = vtkPolyData()
        surface.ShallowCopy(lit)
        scalars = numpy_to_vtk([math.log10(max(v, 1e-3)) for v in values], deep=1)
        scalars.SetName("log10 E")
        surface.GetPointData().SetScalars(scalars)
        mapper = vtkPolyDataMapper()
        mapper.SetInputData(surface)
        mapper.SetLookupTable(lut)
        mapper.SetScalarModeToUsePointData()
        mapper.SetColorModeToMapScalars()
        actor = vtkActor()
        actor.SetMapper(mapper)
        actor.GetProperty().SetLighting(False)
        renderer = vtkRenderer()
        renderer.SetViewport(i / 3.0, 0.0, (i + 1) / 3.0, 1.0)
        renderer.AddActor(actor)
        label = vtkTextActor()
        label.SetInput(title)
        label.GetTextProperty().SetFontSize(18)
        label.SetPosition(10, 10)
        renderer.AddActor2D(label)
        camera = renderer.GetActiveCamera()
        camera.SetFocalPoint(0.0, 0.15, 0.0)
        camera.SetPosition(0.0, 2.2, 1.6)
        camera.SetViewUp(0.0, 1.0, 0.0)
        camera.SetViewAngle(40)
        window.AddRenderer(renderer)
    window.Render()
    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    writer = vtkPNGWriter()
    writer.SetFileName(path)
    writer.SetInputConnection(grab.GetOutputPort())
    writer.Write()
    print("caustic power check: max caustic %.3g W/m^2, photons %d" % (
        caustics.max(), lit.GetFieldData().GetArray("LinkGI.Photons").GetValue(0)))


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "caustics.png")
