"""The four methods side by side: the Cornell box of vtkGlobalIlluminationSceneSource, its
lamp (1/r^2), lit by vtkGlobalIlluminationFilter with each method at its defaults and drawn
by vtkGlobalIlluminationMapper with the default look; the time of each update in the title.
Documentation/Methods.md says when to use which.

  PYTHONPATH=build/lib/python3.11/dist-packages xvfb-run -a /usr/bin/python3 \\
    Examples/Python/methods.py methods.png
"""
import sys
import time

import linkgi
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingCore import (vtkActor, vtkLightCollection, vtkRenderWindow,
                                         vtkRenderer, vtkTextActor, vtkWindowToImageFilter)
import vtkmodules.vtkRenderingFreeType  # noqa: F401 (the titles)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (the OpenGL back end)

METHODS = [("link structure", "SetMethodToLinks"),
           ("instant radiosity", "SetMethodToInstantRadiosity"),
           ("implicit visibility", "SetMethodToImplicitVisibility"),
           ("photon mapping", "SetMethodToPhotonMapping")]

box = linkgi.vtkGlobalIlluminationSceneSource()
box.SetSceneName("cornell")
lights = vtkLightCollection()
box.CreateLights(lights)

window = vtkRenderWindow()
window.SetOffScreenRendering(True)
window.SetSize(4 * 300, 300)
for i, (name, method) in enumerate(METHODS):
    renderer = vtkRenderer()
    renderer.SetViewport(i / 4.0, 0.0, (i + 1) / 4.0, 1.0)
    lights.InitTraversal()
    for _ in range(lights.GetNumberOfItems()):
        renderer.AddLight(lights.GetNextItem())
    gi = linkgi.vtkGlobalIlluminationFilter()
    gi.SetInputConnection(box.GetOutputPort())
    gi.SetAlbedoArrayName("Albedo")
    gi.SetEmissionArrayName("Emission")
    getattr(gi, method)()
    gi.SetLightsFromRenderer(renderer)
    start = time.perf_counter()
    gi.Update()
    seconds = time.perf_counter() - start
    mapper = linkgi.vtkGlobalIlluminationMapper()
    mapper.SetInputConnection(gi.GetOutputPort())
    mapper.ScalarVisibilityOff()
    actor = vtkActor()
    actor.SetMapper(mapper)
    renderer.AddActor(actor)
    title = vtkTextActor()
    title.SetInput("%s, %.1f s" % (name, seconds))
    title.GetTextProperty().SetFontSize(16)
    title.SetPosition(8, 8)
    renderer.AddActor2D(title)
    camera = renderer.GetActiveCamera()  # the published Cornell box camera, in metres
    camera.SetPosition(0.278, 0.273, -0.8)
    camera.SetFocalPoint(0.278, 0.273, 0)
    camera.SetViewUp(0, 1, 0)
    camera.SetViewAngle(39.3)
    renderer.ResetCameraClippingRange()
    window.AddRenderer(renderer)
    print("%s: %.2f s" % (name, seconds))

window.Render()
grab = vtkWindowToImageFilter()
grab.SetInput(window)
writer = vtkPNGWriter()
writer.SetFileName(sys.argv[1] if len(sys.argv) > 1 else "methods.png")
writer.SetInputConnection(grab.GetOutputPort())
writer.Write()
