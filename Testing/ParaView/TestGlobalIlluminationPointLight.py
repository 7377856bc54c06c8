"""pvbatch: a Light Inspector point light lights the Global Illumination representation as it
lights Surface. The light (intensity 1, VTK's default attenuation: no falloff with distance)
sits 7 units in front of a plane of colour patches (ParaView's Cool to Warm at 9 points, the
primaries and secondaries, white, a dark grey), the view's light kit off. Nothing bounces
and nothing is shadowed, so every patch must be within CIEDE2000 2.0 of Surface's pixel, and
the image no darker than Surface's.
"""
import os

import linkgi_paraview_testing as t
from paraview.simple import *  # noqa: F401,F403 (the pvbatch idiom)

import linkgi_colour_difference as colour
from vtkmodules.vtkCommonCore import vtkIntArray
from vtkmodules.vtkFiltersSources import vtkPlaneSource
from vtkmodules.vtkIOImage import vtkPNGReader

PATCH = 40  # pixels per colour
DISTANCE = 7.0

arguments = t.parse_arguments()
t.load_plugin(arguments.plugin, globals())
colours = colour.cool_to_warm_and_primaries()
n = len(colours)

plane = vtkPlaneSource()  # facing +z, one cell per colour
plane.SetOrigin(0, 0, 0)
plane.SetPoint1(n, 0, 0)
plane.SetPoint2(0, 1, 0)
plane.SetResolution(n, 1)
plane.Update()
index = vtkIntArray()
index.SetName("index")
for i in range(n):
    index.InsertNextValue(i)
plane.GetOutput().GetCellData().AddArray(index)
producer = TrivialProducer()
producer.GetClientSideObject().SetOutput(plane.GetOutput())

view = CreateView("RenderView")
view.ViewSize = [n * PATCH, PATCH]
view.OrientationAxesVisibility = 0
view.UseColorPaletteForBackground = 0
view.Background = [0, 0, 0]
view.UseLight = 0  # no light kit: the point light alone
light = CreateLight()
light.Coords, light.Type = "Scene", "Positional"
light.Position = [n / 2.0, 0.5, DISTANCE]
light.FocalPoint = [n / 2.0, 0.5, 0]
light.ConeAngle = 90  # 90 or more: a point light, no spot
light.Intensity = 1.0
view.AdditionalLights = [light]

display = Show(producer, view)
Render(view)  # the first render resets the camera
view.CameraPosition = [n / 2.0, 0.5, 10]
view.CameraFocalPoint = [n / 2.0, 0.5, 0]
view.CameraViewUp = [0, 1, 0]
view.CameraParallelProjection = 1
view.CameraParallelScale = 0.5
ColorBy(display, ("CELLS", "index"))
lut = GetColorTransferFunction("index")
lut.ColorSpace = "RGB"
lut.Discretize = 0
lut.RGBPoints = [v for i, (_, rgb) in enumerate(colours) for v in (i,) + tuple(rgb)]
lut.AutomaticRescaleRangeMode = "Never"


def centre_pixels(name):
    path = os.path.join(arguments.output_dir, "PointLight-%s.png" % name)
    os.makedirs(arguments.output_dir, exist_ok=True)
    Render(view)
    SaveScreenshot(path, view, ImageResolution=[n * PATCH, PATCH], TransparentBackground=0)
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    scalars = image.GetPointData().GetScalars()
    width = image.GetDimensions()[0]
    return [scalars.GetTuple(((PATCH // 2) * width + i * PATCH + PATCH // 2))[:3] for i in range(n)]


display.Representation = "Surface"
surface = centre_pixels("Surface")
display.Representation = "Global Illumination"
display.GlobalIlluminationRays = 16
gi = centre_pixels("GlobalIllumination")
display.SMProxy.UpdatePropertyInformation()
mean_indirect = display.SMProxy.GetProperty("GlobalIlluminationMeanIndirect").GetElement(0)
t.check(mean_indirect == 0.0, "no light reaches the open plane indirectly (%g)" % mean_indirect)

worst = 0.0
for (name, _), s, g in zip(colours, surface, gi):
    difference = colour.pixel_difference(s, g)
    worst = max(worst, difference)
    print("%-20s Surface %-22s Global Illumination %-22s CIEDE2000 %.2f"
          % (name, tuple(int(v) for v in s), tuple(int(v) for v in g), difference))
t.check(worst <= 2.0, "every colour within CIEDE2000 2.0 of Surface (largest %.2f)" % worst)
t.check(sum(map(sum, gi)) >= 0.98 * sum(map(sum, surface)),
        "Global Illumination is no darker than Surface (%d vs %d)"
        % (sum(map(sum, gi)), sum(map(sum, surface))))
t.check(min(sum(p) for p in surface) > 0, "every patch is lit by the point light")
