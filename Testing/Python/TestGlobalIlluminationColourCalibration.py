"""vtkGlobalIlluminationMapper keeps the data's colours: a plane facing the lights in an
open scene with a black sky (no light reaches it indirectly, none is blocked) shows every
colour of a colour map as the plain VTK mapper does, within CIEDE2000 2.0. The colours are
ParaView's default map, Cool to Warm, at 9 points, and the primaries and secondaries; the
lights are one directional light of intensity 1, VTK's light kit (ParaView's default
lights: key, fill, two back lights and a head light, of other intensities and tints), and a
point light of intensity 1 seven units in front of the plane with VTK's default attenuation
(no falloff).
Over-exposed by half, the default display keeps every colour's hue (or turns it white).

Usage: TestGlobalIlluminationColourCalibration.py [output directory for the images]
"""
import colorsys
import os
import sys

import linkgi
import linkgi_colour_difference as colour
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (the OpenGL factories)
from vtkmodules.vtkCommonCore import vtkIntArray, vtkLookupTable
from vtkmodules.vtkFiltersSources import vtkPlaneSource
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingCore import (vtkActor, vtkLight, vtkLightKit, vtkPolyDataMapper,
                                         vtkRenderer, vtkRenderWindow, vtkWindowToImageFilter)

PATCH = 40  # pixels per colour


def patches(colours):
    """A plane facing +z, one cell per colour, coloured through a lookup table."""
    plane = vtkPlaneSource()
    plane.SetOrigin(0, 0, 0)
    plane.SetPoint1(len(colours), 0, 0)
    plane.SetPoint2(0, 1, 0)
    plane.SetResolution(len(colours), 1)
    plane.Update()
    surface = plane.GetOutput()
    index = vtkIntArray()
    index.SetName("index")
    for i in range(len(colours)):
        index.InsertNextValue(i)
    surface.GetCellData().AddArray(index)
    table = vtkLookupTable()
    table.SetNumberOfTableValues(len(colours))
    table.SetTableRange(-0.5, len(colours) - 0.5)
    for i, (_, rgb) in enumerate(colours):
        table.SetTableValue(i, rgb[0], rgb[1], rgb[2], 1.0)
    return surface, table


def colour_by(mapper, table):
    mapper.SetLookupTable(table)
    mapper.UseLookupTableScalarRangeOn()
    mapper.SetScalarModeToUseCellFieldData()
    mapper.SelectColorArray("index")
    mapper.ScalarVisibilityOn()


def add_lights(renderer, kind, width):
    if kind == "light kit":
        vtkLightKit().AddLightsToRenderer(renderer)
        return
    if kind == "point light":  # VTK's default attenuation: no falloff, as VTK draws it
        light = vtkLight()
        light.SetLightTypeToSceneLight()
        light.SetPositional(True)
        light.SetConeAngle(180)
        light.SetPosition(width / 2.0, 0.5, 7.0)  # 7 units in front of the plane's middle
        light.SetFocalPoint(width / 2.0, 0.5, 0)
        light.SetIntensity(1.0)
        renderer.AddLight(light)
        return
    light = vtkLight()  # directional, towards the plane, intensity 1
    light.SetLightTypeToSceneLight()
    light.SetPositional(False)
    light.SetPosition(0, 0, 1)
    light.SetFocalPoint(0, 0, 0)
    light.SetIntensity(1.0)
    renderer.AddLight(light)


def render(surface, table, lights, global_illumination, image_path, exposure=1.0):
    """The patches' centre pixels, drawn by the plain or the GI mapper."""
    n = table.GetNumberOfTableValues()
    renderer = vtkRenderer()
    window = vtkRenderWindow()
    window.SetOffScreenRendering(True)
    window.SetMultiSamples(0)
    window.SetSize(n * PATCH, PATCH)
    window.AddRenderer(renderer)
    add_lights(renderer, lights, n)
    camera = renderer.GetActiveCamera()
    camera.ParallelProjectionOn()
    camera.SetFocalPoint(n / 2.0, 0.5, 0)
    camera.SetPosition(n / 2.0, 0.5, 10)
    camera.SetViewUp(0, 1, 0)
    camera.SetParallelScale(0.5)
    renderer.ResetCameraClippingRange()
    if global_illumination:
        mapper = linkgi.vtkGlobalIlluminationMapper()
        mapper.GetShading().SetExposure(exposure)
        colour_by(mapper, table)
        actor = vtkActor()
        window.Render()  # places the light kit's camera lights
        gi = linkgi.vtkGlobalIlluminationFilter()
        gi.SetRaysPerVertex(16)
        gi.SetEnvironmentColor(0, 0, 0)  # a black sky
        gi.SetLightsFromRenderer(renderer)
        drawn = linkgi.vtkGlobalIlluminationDrawnAlbedo()
        gi.SetInputDataObject(drawn.Apply(surface, mapper, actor.GetProperty(), gi))
        gi.Update()
        indirect = gi.GetOutput().GetPointData().GetArray("IndirectIrradiance")
        largest = max(indirect.GetRange(k)[1] for k in range(3))
        if largest != 0.0:
            sys.exit("FAILED: light reaches the open plane indirectly (%g)" % largest)
        mapper.SetInputConnection(gi.GetOutputPort())
    else:
        mapper = vtkPolyDataMapper()
        colour_by(mapper, table)
        mapper.SetInputData(surface)
        actor = vtkActor()
    actor.SetMapper(mapper)
    renderer.AddActor(actor)
    window.Render()
    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.Update()
    image = grab.GetOutput()
    if image_path:
        writer = vtkPNGWriter()
        writer.SetFileName(image_path)
        writer.SetInputData(image)
        writer.Write()
    scalars = image.GetPointData().GetScalars()
    width = image.GetDimensions()[0]
    return [scalars.GetTuple3((PATCH // 2) * width + i * PATCH + PATCH // 2) for i in range(n)]


def main():
    output = sys.argv[1] if len(sys.argv) > 1 else None
    colours = colour.cool_to_warm_and_primaries()
    surface, table = patches(colours)
    worst = 0.0
    for lights in ("directional", "light kit", "point light"):
        paths = [os.path.join(output, "ColourCalibration-%s-%s.png" % (lights.replace(" ", ""), m))
                 if output else None for m in ("plain", "gi")]
        plain = render(surface, table, lights, False, paths[0])
        gi = render(surface, table, lights, True, paths[1])
        if len(set(plain)) != len(colours) or min(sum(p) for p in plain) == 0:
            sys.exit("FAILED: the patches do not show their colours under the %s light(s)" % lights)
        for (name, _), p, g in zip(colours, plain, gi):
            difference = colour.pixel_difference(p, g)
            worst = max(worst, difference)
            print("%-11s %-20s plain %-22s GI %-22s CIEDE2000 %.2f" %
                  (lights, name, tuple(int(v) for v in p), tuple(int(v) for v in g), difference))
            if difference > 2.0:
                sys.exit("FAILED: %s under the %s light(s) differs by CIEDE2000 %.2f"
                         % (name, lights, difference))
    print("ok: largest CIEDE2000 difference %.2f" % worst)

    # Over-exposed by half: a saturated colour beyond display white keeps its hue and gets
    # lighter, towards white; one whose luminance passes white turns white (no other hue).
    plain = render(surface, table, "directional", False, None)
    bright = render(surface, table, "directional", True, None, exposure=1.5)
    for (name, _), p, b in zip(colours, plain, bright):
        h, s, v = colorsys.rgb_to_hsv(*(c / 255.0 for c in p))
        hb, sb, vb = colorsys.rgb_to_hsv(*(c / 255.0 for c in b))
        shift = 360.0 * min(abs(h - hb), 1.0 - abs(h - hb))
        print("exposure 1.5 %-20s plain %-22s GI %-22s hue shift %.1f degrees"
              % (name, tuple(int(c) for c in p), tuple(int(c) for c in b), shift))
        white = sb < 0.02 and vb > 0.99
        if s > 0.2 and not white and (shift > 2.0 or sb > s + 0.01 or vb < v):
            sys.exit("FAILED: over-exposed, %s changes hue or darkens" % name)
    print("ok: over-exposed colours keep their hue")


if __name__ == "__main__":
    main()
