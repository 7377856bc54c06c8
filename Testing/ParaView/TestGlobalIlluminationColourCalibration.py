"""pvbatch: the Global Illumination representation shows a colour map's colours as the
Surface representation does where light is only direct and unblocked: a plane facing the
camera in an open scene (black sky), default view lights (the light kit: key, fill, two
back and head lights), coloured through a colour map holding ParaView's default Cool to
Warm at 9 points, the primaries and secondaries, white and a dark grey. Every colour must
be within CIEDE2000 2.0 of Surface's pixel.
"""
import os

import linkgi_paraview_testing as t
from paraview.simple import *  # noqa: F401,F403 (the pvbatch idiom)

import linkgi_colour_difference as colour
from vtkmodules.vtkCommonCore import vtkIntArray
from vtkmodules.vtkFiltersSources import vtkPlaneSource
from vtkmodules.vtkIOImage import vtkPNGReader

PATCH = 40  # pixels per colour

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
t.check(view.UseLight == 1 and len(view.AdditionalLights) == 0, "the view has its default lights")

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
    path = os.path.join(arguments.output_dir, "ColourCalibration-%s.png" % name)
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
t.check(len(set(surface)) == n and min(sum(p) for p in surface) > 0,
        "every patch shows its own colour, lit by the light kit")
