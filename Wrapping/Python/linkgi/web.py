"""Global illumination live in the browser: python -m linkgi.web FILE [trame options]

Reads any surface or dataset VTK reads (.vtp, .vtu, .vtk, .ply, .stl, .obj, ...; volumes
are lit as their surface), lights it on the server with vtkGlobalIlluminationFilter under a
lamp (a point light falling off as 1/r^2) and draws the displayed colours
(vtkGlobalIlluminationDisplayColors) with vtk.js in the browser. Sliders move the lamp (a
light move re-traces only the shadow rays and the bounces, and the browser receives the new
colours alone), pick the method, the bounces and the light term shown; a click on the
model puts the lamp above the clicked point. The lamp is the small yellow ball.

Needs trame, trame-vtk and trame-vuetify (pip install trame trame-vtk trame-vuetify) in a
Python that has VTK and LinkGI, e.g. a virtual environment of Debian's /usr/bin/python3 made
with --system-site-packages. trame's own options apply: --port N, --server (do not open a
browser), --host.
"""
import os
import time

import numpy as np

import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (the OpenGL factories)
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkFiltersCore import vtkTriangleFilter
from vtkmodules.vtkFiltersGeometry import vtkDataSetSurfaceFilter
from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.vtkIOGeometry import vtkOBJReader, vtkSTLReader
from vtkmodules.vtkIOLegacy import vtkDataSetReader
from vtkmodules.vtkIOPLY import vtkPLYReader
from vtkmodules.vtkIOXML import vtkXMLGenericDataObjectReader
from vtkmodules.vtkRenderingCore import vtkLight

from . import methods
from .LinkGIFiltersGlobalIllumination import vtkGlobalIlluminationFilter
from .LinkGIRenderingGlobalIllumination import (vtkGlobalIlluminationDisplayColors,
                                                vtkGlobalIlluminationShading)

READERS = {".ply": vtkPLYReader, ".stl": vtkSTLReader, ".obj": vtkOBJReader,
           ".vtk": vtkDataSetReader}
# The interactive methods (the path tracer re-traces everything at every lamp move).
METHODS = [name for name in methods() if name != "reference"]
MODES = ["combined", "direct", "indirect"]


def read_surface(path):
    """The surface of the first dataset in `path`, as a vtkPolyData."""
    if not os.path.exists(path):
        raise FileNotFoundError(f"linkgi.web: {path} does not exist")
    reader = READERS.get(os.path.splitext(path)[1].lower(), vtkXMLGenericDataObjectReader)()
    reader.SetFileName(path)
    reader.Update()
    data = reader.GetOutputDataObject(0)
    if data is None or not hasattr(data, "GetNumberOfPoints") or data.GetNumberOfPoints() == 0:
        raise ValueError(f"linkgi.web: no surface in {path}")
    surface = vtkDataSetSurfaceFilter()
    surface.SetInputData(data)
    surface.Update()
    return surface.GetOutput()


class LiveScene:
    """The server's side: the surface lit by a lamp, and the colours the browser draws."""

    def __init__(self, surface):
        self.surface = surface
        lo = np.array(surface.GetBounds()[0::2])
        hi = np.array(surface.GetBounds()[1::2])
        self.centre = 0.5 * (lo + hi)
        self.size = float(np.linalg.norm(hi - lo)) or 1.0
        self.lamp = vtkLight()
        self.lamp.SetPositional(True)
        self.lamp.SetConeAngle(180)
        self.lamp.SetAttenuationValues(0, 0, 1)
        self.lamp.SetIntensity(0.5 * self.size ** 2)  # about 1 W/m^2 at the surface
        self.gi = vtkGlobalIlluminationFilter()
        self.gi.SetInputData(surface)
        self.gi.AddLight(self.lamp)
        self.colors = vtkGlobalIlluminationDisplayColors()
        self.colors.SetInputConnection(self.gi.GetOutputPort())
        self.colors.SetShading(vtkGlobalIlluminationShading())
        self.baked = None
        self.milliseconds = 0.0
        self.ball = vtkSphereSource()
        self.ball.SetRadius(0.015 * self.size)

    def light_range(self):
        """Where the lamp may go: the bounds grown by their diagonal, per axis."""
        return (self.centre - self.size).tolist(), (self.centre + self.size).tolist()

    def place_lamp(self, position):
        self.lamp.SetPosition(*position)
        self.ball.SetCenter(*position)

    def _relative(self, poly):
        """`poly` with its points relative to the centre: vtk.js draws float32, which would
        round away the detail of data far from the origin (UTM coordinates)."""
        shifted = vtkPolyData()
        shifted.ShallowCopy(poly)
        points = vtkPoints()
        points.SetData(numpy_to_vtk(vtk_to_numpy(poly.GetPoints().GetData()) - self.centre,
                                    deep=True))
        shifted.SetPoints(points)
        return shifted

    def ball_mesh(self):
        from trame_vtk.modules.vtk.serializers import mesh
        self.ball.Update()
        return mesh(self._relative(self.ball.GetOutput()))

    def set_method(self, method, bounces):
        self.gi.SetMethod(methods()[method])
        self.gi.SetNumberOfBounces(int(bounces))

    def relight(self):
        """Solves what changed and bakes the colours; returns the milliseconds it took."""
        start = time.perf_counter()
        self.colors.Update()
        self.baked = self.colors.GetOutput()
        self.milliseconds = 1000.0 * (time.perf_counter() - start)
        return self.milliseconds

    def colors_of(self, mode):
        """The displayed colours of `mode` (uint8 RGB per point)."""
        name = vtkGlobalIlluminationDisplayColors.GetColorsArrayName(MODES.index(mode))
        return vtk_to_numpy(self.baked.GetPointData().GetArray(name))

    def mesh(self):
        """The triangles, as trame-vtk's mesh state (vtk.js draws them)."""
        from trame_vtk.modules.vtk.serializers import mesh
        triangles = vtkTriangleFilter()
        triangles.SetInputData(self.surface)
        triangles.PassVertsOff()
        triangles.PassLinesOff()
        triangles.Update()
        return mesh(self._relative(triangles.GetOutput()))


def main(argv=None):
    from trame.app import get_server
    from trame.ui.vuetify3 import SinglePageWithDrawerLayout
    from trame.widgets import vtk as vtk_widgets
    from trame.widgets import vuetify3 as v
    from trame_vtk.modules.vtk.serializers.mesh import b64_encode_numpy

    server = get_server(client_type="vue3")
    server.cli.add_argument("file", help="a mesh or dataset VTK reads")
    args, _ = server.cli.parse_known_args(argv)
    scene = LiveScene(read_surface(args.file))
    state, ctrl = server.state, server.controller
    low, high = scene.light_range()
    start = scene.centre + np.array([0.3, 0.4, 0.8]) * scene.size * 0.6
    scene.place_lamp(start)
    scene.set_method(METHODS[0], 2)
    scene.relight()
    geometry = scene.mesh()

    def surface_state(mode):
        # The geometry's strings are made once; a light move sends them with new colours.
        colors = scene.colors_of(mode)
        return dict(geometry, field={
            "name": "colors", "values": b64_encode_numpy(colors.ravel()),
            "numberOfComponents": 3, "type": "Uint8Array", "location": "PointData",
            "dataRange": [0, 255]})

    state.update({"light_x": float(start[0]), "light_y": float(start[1]),
                  "light_z": float(start[2]), "method": METHODS[0], "bounces": 2,
                  "mode": MODES[0], "light_ms": round(scene.milliseconds, 2),
                  "surface": surface_state(MODES[0]), "lamp": scene.ball_mesh(),
                  "methods": METHODS, "modes": MODES, "version": 0})

    def publish():
        state.light_ms = round(scene.milliseconds, 2)
        state.surface = surface_state(state.mode)
        state.lamp = scene.ball_mesh()
        state.version += 1  # what a client (or a test) watches for new colours

    @state.change("light_x", "light_y", "light_z")
    def move_lamp(light_x, light_y, light_z, **_):
        scene.place_lamp((light_x, light_y, light_z))
        scene.relight()
        publish()

    def place_lamp_above(event):
        """A click on the model puts the lamp above the clicked point (outward from the
        model's centre, a third of its size away)."""
        picked = (event or {}).get("worldPosition") if isinstance(event, dict) else None
        if not picked:
            return
        point = np.array(picked[:3]) + scene.centre  # the browser's points are relative
        outward = point - scene.centre
        length = np.linalg.norm(outward)
        outward = outward / length if length > 0 else np.array([0.0, 0.0, 1.0])
        lamp = point + outward * scene.size / 3.0
        state.update({"light_x": float(lamp[0]), "light_y": float(lamp[1]),
                      "light_z": float(lamp[2])})

    @state.change("method", "bounces")
    def change_method(method, bounces, **_):
        scene.set_method(method, bounces)
        scene.relight()
        publish()

    @state.change("mode")
    def change_mode(mode, **_):
        publish()

    with SinglePageWithDrawerLayout(server) as layout:
        layout.title.set_text("LinkGI: " + os.path.basename(args.file))
        with layout.toolbar:
            v.VSpacer()
            v.VChip("light update {{ light_ms }} ms", size="small")
            v.VBtn(icon="mdi-crop-free", click=lambda: ctrl.reset_camera(), density="compact")
        with layout.drawer:
            with v.VContainer():
                v.VSelect(v_model=("method",), items=("methods",), label="Method")
                v.VSelect(v_model=("mode",), items=("modes",), label="Light shown")
                v.VSlider(v_model=("bounces",), min=0, max=8, step=1, label="Bounces",
                          thumb_label=True)
                for k, axis in enumerate("xyz"):
                    v.VSlider(v_model=(f"light_{axis}",), min=low[k], max=high[k],
                              step=(high[k] - low[k]) / 200, label=f"Lamp {axis}")
        with layout.content:
            with v.VContainer(fluid=True, classes="pa-0 fill-height"):
                with vtk_widgets.VtkView(ref="view", picking_modes=("['click']",),
                                         click=(place_lamp_above, "[$event]")) as view:
                    # Unlit, the colours as they are: exactly the baked values.
                    with vtk_widgets.VtkGeometryRepresentation(
                            mapper=("{ colorMode: 2, scalarVisibility: true }",),
                            property=("{ ambient: 1, diffuse: 0, specular: 0, "
                                      "lighting: false }",)):
                        vtk_widgets.VtkMesh("surface", state=("surface",))
                    with vtk_widgets.VtkGeometryRepresentation(
                            property=("{ color: [1, 0.85, 0.2], lighting: false }",)):
                        vtk_widgets.VtkMesh("lamp", state=("lamp",))
    # The model framed when a browser connects (and by the toolbar's button).
    ctrl.on_client_connected.add(view.reset_camera)
    ctrl.reset_camera = view.reset_camera
    server.start()


if __name__ == "__main__":
    main()
