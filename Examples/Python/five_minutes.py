"""The README's five minutes with VTK in Python: a sphere on a plane under a lamp, lit by
vtkGlobalIlluminationFilter and drawn by vtkGlobalIlluminationMapper, written to a PNG.

  PYTHONPATH=build/lib/python3.11/dist-packages xvfb-run -a /usr/bin/python3 \\
    Examples/Python/five_minutes.py five_minutes.png
"""
import sys

import linkgi
from vtkmodules.vtkFiltersCore import vtkAppendPolyData
from vtkmodules.vtkFiltersSources import vtkPlaneSource, vtkSphereSource
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingCore import (vtkActor, vtkLight, vtkRenderWindow, vtkRenderer,
                                         vtkWindowToImageFilter)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (the OpenGL back end)

sphere = vtkSphereSource()
sphere.SetCenter(0, 0, 0.5)
sphere.SetRadius(0.5)
sphere.SetThetaResolution(48)
sphere.SetPhiResolution(24)
plane = vtkPlaneSource()
plane.SetOrigin(-2, -2, 0)
plane.SetPoint1(2, -2, 0)
plane.SetPoint2(-2, 2, 0)
plane.SetResolution(60, 60)
scene = vtkAppendPolyData()
scene.AddInputConnection(sphere.GetOutputPort())
scene.AddInputConnection(plane.GetOutputPort())

renderer = vtkRenderer()
lamp = vtkLight()
lamp.SetPositional(True)
lamp.SetConeAngle(180)                 # a point light, not a spot
lamp.SetPosition(1, -1, 3)
lamp.SetIntensity(10)
lamp.SetAttenuationValues(0, 0, 1)     # a lamp: 1/r^2 (VTK's default does not fall off)
renderer.AddLight(lamp)

gi = linkgi.vtkGlobalIlluminationFilter()       # per-vertex direct and indirect light
gi.SetInputConnection(scene.GetOutputPort())
gi.SetLightsFromRenderer(renderer)              # the lights the renderer draws
mapper = linkgi.vtkGlobalIlluminationMapper()   # shadows per pixel + the bounced light
mapper.SetInputConnection(gi.GetOutputPort())
actor = vtkActor()
actor.SetMapper(mapper)
renderer.AddActor(actor)
camera = renderer.GetActiveCamera()
camera.SetPosition(0, -5, 3)
camera.SetFocalPoint(0, 0, 0.3)
camera.SetViewUp(0, 0, 1)
renderer.ResetCameraClippingRange()

window = vtkRenderWindow()
window.SetOffScreenRendering(True)
window.SetSize(600, 400)
window.AddRenderer(renderer)
window.Render()
grab = vtkWindowToImageFilter()
grab.SetInput(window)
writer = vtkPNGWriter()
writer.SetFileName(sys.argv[1] if len(sys.argv) > 1 else "five_minutes.png")
writer.SetInputConnection(grab.GetOutputPort())
writer.Write()
