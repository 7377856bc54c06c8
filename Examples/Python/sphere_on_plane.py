"""A sphere resting on a plane, lit by one point light; writes out.vtp with the point arrays
DirectIrradiance, IndirectIrradiance and Radiance (linear RGB).
Usage: /usr/bin/python3 sphere_on_plane.py out.vtp          (LinkGI installed)
       PYTHONPATH=build/lib/python3.11/dist-packages /usr/bin/python3 sphere_on_plane.py out.vtp"""
import sys
import linkgi
from vtkmodules.vtkFiltersCore import vtkAppendPolyData
from vtkmodules.vtkFiltersSources import vtkPlaneSource, vtkSphereSource
from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter
from vtkmodules.vtkRenderingCore import vtkLight

sphere = vtkSphereSource()  # radius 0.5, touching the plane z = 0
sphere.SetCenter(0, 0, 0.5)
sphere.SetThetaResolution(48)
sphere.SetPhiResolution(24)
plane = vtkPlaneSource()  # 4 x 4, facing +z
plane.SetOrigin(-2, -2, 0)
plane.SetPoint1(2, -2, 0)
plane.SetPoint2(-2, 2, 0)
plane.SetResolution(60, 60)
scene = vtkAppendPolyData()
scene.AddInputConnection(sphere.GetOutputPort())
scene.AddInputConnection(plane.GetOutputPort())

light = vtkLight()  # a point light of 16 W/sr, 4 m up: irradiance 1 on the plane below it
light.SetPositional(True)
light.SetAttenuationValues(0, 0, 1)  # a lamp: 1/r^2 (VTK's default does not fall off)
light.SetConeAngle(90)
light.SetPosition(0.5, 0.5, 4)
light.SetIntensity(16)

gi = linkgi.vtkGlobalIlluminationFilter()
gi.SetInputConnection(scene.GetOutputPort())
gi.AddLight(light)
gi.SetEnvironmentColor(0.05, 0.05, 0.08)  # a dim sky
writer = vtkXMLPolyDataWriter()
writer.SetInputConnection(gi.GetOutputPort())
writer.SetFileName(sys.argv[1] if len(sys.argv) > 1 else "sphere_on_plane.vtp")
sys.exit(0 if writer.Write() == 1 else 1)
