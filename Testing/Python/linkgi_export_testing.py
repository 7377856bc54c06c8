"""Scenes and image comparisons shared by the tests of the displayed colours and the
exporters (TestDisplayColors, TestExportHtml, TestExportGlb)."""
import functools
import json
import os
import shutil
import subprocess
import tempfile

import numpy as np

import linkgi
import linkgi_colour_difference as colour
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (the OpenGL factories)
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
from vtkmodules.vtkFiltersCore import vtkAppendPolyData, vtkElevationFilter, vtkReverseSense
from vtkmodules.vtkFiltersSources import vtkPlaneSource, vtkSphereSource
from vtkmodules.vtkIOImage import vtkPNGReader, vtkPNGWriter
from vtkmodules.vtkRenderingCore import (vtkActor, vtkLight, vtkPolyDataMapper, vtkRenderer,
                                         vtkRenderWindow, vtkWindowToImageFilter)

SIZE = (480, 320)


def _sphere_on_plane(resolution=60, against_winding=False):
    sphere = vtkSphereSource()
    sphere.SetCenter(0, 0, 0.5)
    sphere.SetRadius(0.5)
    sphere.SetThetaResolution(64)
    sphere.SetPhiResolution(32)
    plane = vtkPlaneSource()
    plane.SetOrigin(-2, -2, 0)
    plane.SetPoint1(2, -2, 0)
    plane.SetPoint2(-2, 2, 0)
    plane.SetResolution(resolution, resolution)
    scene = vtkAppendPolyData()
    scene.AddInputConnection(sphere.GetOutputPort())
    if against_winding:
        # The plane's triangles wound downward, its normals still up (as in models whose
        # normals and winding disagree).
        reverse = vtkReverseSense()
        reverse.SetInputConnection(plane.GetOutputPort())
        reverse.ReverseCellsOn()
        reverse.ReverseNormalsOff()
        scene.AddInputConnection(reverse.GetOutputPort())
        scene.reverse = reverse  # kept alive with the append filter
    else:
        scene.AddInputConnection(plane.GetOutputPort())
    return scene


def _window(renderer, position=(0, -5, 3), focal_point=(0, 0, 0.3), view_up=(0, 0, 1),
            view_angle=30.0, size=SIZE):
    """An off-screen window of `renderer` at that camera, rendered once."""
    camera = renderer.GetActiveCamera()
    camera.SetPosition(position)
    camera.SetFocalPoint(focal_point)
    camera.SetViewUp(view_up)
    camera.SetViewAngle(view_angle)
    renderer.ResetCameraClippingRange()
    window = vtkRenderWindow()
    window.SetOffScreenRendering(True)
    window.SetSize(*size)
    window.AddRenderer(renderer)
    window.Render()
    return window


def lamp_scene(against_winding=False):
    """A sphere on a plane under a lamp (a point light that falls off with 1/r^2): the
    automatic exposure and the exponential curve of lamp scenes. `against_winding`: the
    plane's normals point against its triangles' winding."""
    renderer = vtkRenderer()
    renderer.SetBackground(0.1, 0.1, 0.1)
    lamp = vtkLight()
    lamp.SetPositional(True)
    lamp.SetConeAngle(180)
    lamp.SetPosition(1, -1, 3)
    lamp.SetIntensity(10)
    lamp.SetAttenuationValues(0, 0, 1)
    renderer.AddLight(lamp)
    shapes = _sphere_on_plane(against_winding=against_winding)  # kept: a port does not keep
    # its algorithm alive
    gi = linkgi.vtkGlobalIlluminationFilter()
    gi.SetInputConnection(shapes.GetOutputPort())
    gi.SetLightsFromRenderer(renderer)
    mapper = linkgi.vtkGlobalIlluminationMapper()
    mapper.SetInputConnection(gi.GetOutputPort())
    actor = vtkActor()
    actor.SetMapper(mapper)
    renderer.AddActor(actor)
    return _window(renderer)


def colour_map_scene():
    """The same shapes coloured by height through a lookup table, under a directional
    light: the hue-preserving display calibrated to VTK's Surface, with a colour map."""
    renderer = vtkRenderer()
    renderer.SetBackground(0.1, 0.1, 0.1)
    sun = vtkLight()
    sun.SetPosition(2, -3, 5)
    sun.SetFocalPoint(0, 0, 0)
    sun.SetIntensity(0.9)
    renderer.AddLight(sun)
    shapes = _sphere_on_plane()
    height = vtkElevationFilter()
    height.SetInputConnection(shapes.GetOutputPort())
    height.SetLowPoint(0, 0, 0)
    height.SetHighPoint(0, 0, 1)
    mapper = linkgi.vtkGlobalIlluminationMapper()
    drawn = linkgi.vtkGlobalIlluminationDrawnAlbedo()
    gi = linkgi.vtkGlobalIlluminationFilter()
    gi.SetLightsFromRenderer(renderer)
    actor = vtkActor()
    actor.SetMapper(mapper)
    mapper.SetScalarModeToUsePointFieldData()
    mapper.SelectColorArray("Elevation")
    mapper.SetScalarRange(0, 1)
    height.Update()
    gi.SetInputDataObject(drawn.Apply(height.GetOutput(), mapper, actor.GetProperty(), gi))
    mapper.SetInputConnection(gi.GetOutputPort())
    renderer.AddActor(actor)
    return _window(renderer)


def baked_window(scene, mode, size=SIZE):
    """VTK drawing the baked colours of `scene` (a linkgi.export.LitScene) unlit, at its
    camera: what any viewer of vertex colours shows."""
    renderer = vtkRenderer()
    renderer.SetBackground(*scene.background)
    for part in scene.parts:
        poly = vtkPolyData()
        points = vtkPoints()
        points.SetData(numpy_to_vtk(part.points, deep=True))
        poly.SetPoints(points)
        cells = vtkCellArray()
        offsets = np.arange(0, 3 * len(part.triangles) + 1, 3, dtype=np.int64)
        cells.SetData(numpy_to_vtk(offsets, deep=True),
                      numpy_to_vtk(part.triangles.ravel().astype(np.int64), deep=True))
        poly.SetPolys(cells)
        rgb = numpy_to_vtk(part.colors[mode], deep=True)
        rgb.SetName("rgb")
        poly.GetPointData().SetScalars(rgb)
        mapper = vtkPolyDataMapper()
        mapper.SetInputData(poly)
        mapper.SetColorModeToDirectScalars()
        actor = vtkActor()
        actor.SetMapper(mapper)
        actor.GetProperty().LightingOff()
        actor.GetProperty().SetBackfaceCulling(part.culled)
        renderer.AddActor(actor)
    camera = scene.camera
    return _window(renderer, camera["position"], camera["focal_point"], camera["view_up"],
                   camera["view_angle"], size)


def grab(window):
    """The window's pixels, top row first, as an H x W x 3 uint8 array."""
    window.Render()
    grabber = vtkWindowToImageFilter()
    grabber.SetInput(window)
    grabber.ReadFrontBufferOff()
    grabber.Update()
    image = grabber.GetOutput()
    width, height, _ = image.GetDimensions()
    pixels = vtk_to_numpy(image.GetPointData().GetScalars()).reshape(height, width, -1)
    return np.ascontiguousarray(pixels[::-1, :, :3])


def read_png(path):
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    width, height, _ = image.GetDimensions()
    pixels = vtk_to_numpy(image.GetPointData().GetScalars()).reshape(height, width, -1)
    return np.ascontiguousarray(pixels[::-1, :, :3])


def write_png(pixels, path):
    height, width, _ = pixels.shape
    from vtkmodules.vtkCommonDataModel import vtkImageData
    image = vtkImageData()
    image.SetDimensions(width, height, 1)
    image.GetPointData().SetScalars(numpy_to_vtk(pixels[::-1].reshape(-1, 3).copy(), deep=True))
    writer = vtkPNGWriter()
    writer.SetFileName(path)
    writer.SetInputData(image)
    writer.Write()


@functools.lru_cache(maxsize=None)
def _difference(a, b):
    return colour.pixel_difference(a, b)


def mean_difference(first, second, background):
    """Mean CIEDE2000 difference over the pixels either image covers (differs from the
    background colour, 8-bit sRGB), and the number of those pixels."""
    bg = np.array(background, dtype=np.int32)
    covered = (np.abs(first.astype(np.int32) - bg).sum(axis=2) > 3) | \
        (np.abs(second.astype(np.int32) - bg).sum(axis=2) > 3)
    a = first[covered]
    b = second[covered]
    total = sum(_difference(tuple(int(v) for v in p), tuple(int(v) for v in q))
                for p, q in zip(a, b))
    return total / max(len(a), 1), int(covered.sum())


def open_in_chromium(page, fragment, screenshot):
    """Screenshot of `page`#`fragment` in headless Chromium (a fresh profile, the window's
    size), and the URLs of the requests the page made."""
    chromium = shutil.which("chromium") or shutil.which("chromium-browser")
    assert chromium, "Chromium is missing (scripts/setup.sh installs it)"
    # Chromium's helper processes may still write to the profile after the browser exits.
    with tempfile.TemporaryDirectory(ignore_cleanup_errors=True) as profile:
        net_log = os.path.join(profile, "net.json")
        command = [
            chromium, "--headless=new", "--no-sandbox", "--disable-gpu", "--use-gl=swiftshader",
            "--enable-unsafe-swiftshader", f"--window-size={SIZE[0]},{SIZE[1]}",
            "--force-device-scale-factor=1", "--hide-scrollbars", f"--user-data-dir={profile}",
            "--no-first-run", "--disable-background-networking", "--disable-component-update",
            "--disable-sync", "--virtual-time-budget=15000", f"--log-net-log={net_log}",
            f"--screenshot={screenshot}", f"file://{os.path.abspath(page)}#{fragment}"]
        subprocess.run(command, check=True, timeout=120, stdout=subprocess.DEVNULL,
                       stderr=subprocess.DEVNULL)
        with open(net_log) as f:
            log = json.load(f)
    start = log["constants"]["logEventTypes"]["URL_REQUEST_START_JOB"]
    # Chromium's own requests (updates, accounts) have no origin; the page's have its own.
    requests = [e.get("params", {}) for e in log["events"] if e["type"] == start]
    return [r["url"] for r in requests if "url" in r and r.get("initiator") != "not an origin"
            and not r["url"].startswith(("file:", "data:", "blob:"))]


def panels_mask(shape, legend):
    """The pixels outside the page's panels (the toggle top left, the legend bottom right)."""
    keep = np.ones(shape[:2], dtype=bool)
    keep[:48, :260] = False
    if legend:
        keep[-80:, -250:] = False
    return keep


def output_dir(argv):
    path = argv[1] if len(argv) > 1 else "."
    os.makedirs(path, exist_ok=True)
    return path
