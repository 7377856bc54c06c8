"""The colour patches of the pvbatch colour tests: a plane of one cell per colour, facing the
camera in an open scene (black sky), coloured through a colour map holding `colours`, drawn
as Surface and as Global Illumination; each test brings its own lights. Nothing bounces on
the open plane and nothing is shadowed, so Global Illumination must show Surface's colours.
"""
import os

import linkgi_colour_difference as colour
import linkgi_paraview_testing as t
from paraview.simple import (ColorBy, CreateView, GetColorTransferFunction, Render,
                             SaveScreenshot, Show, TrivialProducer)
from vtkmodules.vtkCommonCore import vtkIntArray
from vtkmodules.vtkFiltersSources import vtkPlaneSource
from vtkmodules.vtkIOImage import vtkPNGReader

PATCH = 40  # pixels per colour


def patch_view(colours):
    """The plane of patches (x from 0 to n, y from 0 to 1, facing +z) and a view of it whose
    lights are the caller's to set before show_patches."""
    n = len(colours)
    plane = vtkPlaneSource()
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
    return producer, view


def compare_with_surface(producer, view, colours, name, output_dir):
    """Shows the patches as Surface, then as Global Illumination (16 rays); checks that nothing
    bounced and that every patch is within CIEDE2000 2.0 of Surface's; returns both pixel
    lists (the centre of each patch, RGB)."""
    n = len(colours)
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

    def centre_pixels(representation):
        path = os.path.join(output_dir, "%s-%s.png" % (name, representation))
        os.makedirs(output_dir, exist_ok=True)
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
    for (label, _), s, g in zip(colours, surface, gi):
        difference = colour.pixel_difference(s, g)
        worst = max(worst, difference)
        print("%-20s Surface %-22s Global Illumination %-22s CIEDE2000 %.2f"
              % (label, tuple(int(v) for v in s), tuple(int(v) for v in g), difference))
    t.check(worst <= 2.0, "every colour within CIEDE2000 2.0 of Surface (largest %.2f)" % worst)
    return surface, gi
