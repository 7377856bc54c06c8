"""LinkGI for PyVista: light a mesh, or draw it in a Plotter with shadows and bounced light.

    import pyvista as pv
    import linkgi.pyvista as lgi

    plotter = pv.Plotter()
    plotter.add_light(pv.Light(position=(1, -1, 3), positional=True, cone_angle=180,
                               intensity=10, attenuation_values=(0, 0, 1)))  # a lamp
    lgi.add_mesh(plotter, mesh, color="tan", bounces=3)  # plotter.add_mesh's arguments too
    plotter.show()

    lit = lgi.illuminate(mesh, plotter)  # a PolyData with the irradiance arrays

`add_mesh` takes every argument of `pyvista.Plotter.add_mesh` (colour, scalars, cmap,
clim, scalar bar, ...), lets PyVista configure the actor as it always does, and then draws
the actor with vtkGlobalIlluminationMapper fed by vtkGlobalIlluminationFilter, lit by the
plotter's lights (its light kit by default). `illuminate` runs the filter alone and returns
`DirectIrradiance`, `IndirectIrradiance` and `Radiance` as point arrays.

The solver's settings are keywords: `method` (a name of linkgi.methods(): "links",
"instant-radiosity", "implicit-visibility", "photon-mapping", "reference"; underscores work
too), the short names below, or any property of vtkGlobalIlluminationFilter in snake case
(`light_oversampling=False`, `memory_budget=2**30`). A value outside a property's range is
an error, not clamped; a solver error raises RuntimeError with the filter's message, and
its warnings become Python warnings.

Runs with Debian's VTK 9.1 and PyVista 0.44 to 0.46, the newest that run on VTK 9.1
(scripts/setup.sh installs 0.46.5 into build/venv).
"""
import inspect
import re
import warnings

try:
    import pyvista
except ImportError as error:  # pragma: no cover (the message is the point)
    raise ImportError(
        "linkgi.pyvista needs PyVista: pip install --no-deps pyvista==0.46.5 scooby pooch "
        "'typing-extensions>=4.10' in a virtual environment of Debian's Python made with "
        "--system-site-packages (scripts/setup.sh makes build/venv)") from error

from vtkmodules.vtkCommonCore import vtkCommand
from vtkmodules.vtkCommonDataModel import vtkCompositeDataSet, vtkPolyData
from vtkmodules.vtkRenderingCore import vtkLight, vtkMapper, vtkRenderer
from vtkmodules.vtkRenderingOpenGL2 import vtkCompositePolyDataMapper2

from . import methods
from .LinkGIFiltersGlobalIllumination import vtkGlobalIlluminationFilter
from .LinkGIRenderingGlobalIllumination import (vtkGlobalIlluminationDrawnAlbedo,
                                                vtkGlobalIlluminationMapper)

__all__ = ["illuminate", "add_mesh"]

# Short names for the settings a PyVista user changes most, as PyVista names things.
SETTINGS = {
    "bounces": "NumberOfBounces",
    "rays": "RaysPerVertex",
    "vpls": "NumberOfVPLs",
    "bins": "ImplicitVisibilityBins",
    "photons": "NumberOfPhotons",
    "clusters": "NumberOfClusters",
    "gather_rays": "FinalGatherRays",
    "paths": "ReferencePathsPerVertex",
}


def _property(keyword):
    """The filter property a keyword names: a short name or snake case, matched without
    regard to case so that acronyms work (vpl_clamp_distance: VPLClampDistance)."""
    if keyword in SETTINGS:
        return SETTINGS[keyword]
    wanted = keyword.replace("_", "").lower()
    for name in dir(vtkGlobalIlluminationFilter):
        if name.startswith("Set") and name[3:].lower() == wanted:
            return name[3:]
    return "".join(part[:1].upper() + part[1:] for part in keyword.split("_"))


def _configure(gi, method, albedo, settings):
    if method is not None:
        known = methods()
        name = str(method).lower().replace("_", "-")
        if name not in known:
            raise ValueError(f"linkgi: unknown method {method!r}; the methods are "
                             f"{', '.join(sorted(known))}")
        gi.SetMethod(known[name])
    if albedo is not None:
        if isinstance(albedo, str):
            gi.SetAlbedoArrayName(albedo)
        else:
            rgb = [float(albedo)] * 3 if _is_number(albedo) else [float(v) for v in albedo]
            if len(rgb) != 3 or not all(0.0 <= v <= 1.0 for v in rgb):
                raise ValueError(f"linkgi: albedo={albedo!r}: give a number or three numbers "
                                 "in [0, 1], or the name of a point or cell array")
            gi.SetAlbedo(*rgb)
    for keyword, value in settings.items():
        name = _property(keyword)
        setter = getattr(gi, "Set" + name, None)
        getter = getattr(gi, "Get" + name, None)
        if setter is None or getter is None:
            raise TypeError(f"linkgi: {keyword}= is no setting of vtkGlobalIlluminationFilter "
                            f"(short names: {', '.join(SETTINGS)})")
        with _Messages(gi, quiet=True) as said:
            setter(value)
        if not _same(getter(), value):  # VTK clamps; a limit must not be wrapped silently
            raise ValueError(f"linkgi: {keyword}={value!r}: " + (
                "; ".join(said.warnings) or f"outside the range of vtkGlobalIlluminationFilter's "
                f"{name} (it would be {getter()!r})"))
        for message in said.warnings:
            warnings.warn(message, RuntimeWarning, stacklevel=3)


def _same(got, value):
    if isinstance(value, (list, tuple)):
        return isinstance(got, (list, tuple)) and list(got) == list(value)
    return got == value


def _is_number(value):
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _set_lights(gi, lights):
    if lights is None:
        raise ValueError("linkgi: no lights: give a pyvista.Plotter (its lights), a "
                         "pyvista.Light or vtkLight, or a list of them")
    renderer = getattr(lights, "renderer", lights)  # a Plotter lights as its renderer does
    if isinstance(renderer, vtkRenderer):
        gi.SetLightsFromRenderer(renderer)
        return
    lights = [lights] if isinstance(lights, vtkLight) else list(lights)
    if not lights or not all(isinstance(light, vtkLight) for light in lights):
        raise TypeError("linkgi: lights must be a pyvista.Plotter, pyvista.Light or vtkLight "
                        "objects")
    gi.RemoveAllLights()
    for light in lights:
        gi.AddLight(light)


class _Messages:
    """What the filter says while inside: its errors raise RuntimeError on leaving (the
    executive's "returned failure" that follows one is left out), its warnings are kept in
    `warnings` and, unless `quiet`, become Python warnings."""

    def __init__(self, gi, quiet=False):
        self.gi, self.quiet, self.errors, self.warnings, self.tags = gi, quiet, [], [], []

    def __enter__(self):
        def on_error(obj, event, message):
            self.errors.append(_text(message))

        def on_warning(obj, event, message):
            self.warnings.append(_text(message))
            if not self.quiet:
                warnings.warn(self.warnings[-1], RuntimeWarning, stacklevel=4)

        def on_failure(obj, event, message):
            pass

        on_error.CallDataType = on_warning.CallDataType = on_failure.CallDataType = "string0"
        executive = self.gi.GetExecutive()
        self.tags = [(self.gi, self.gi.AddObserver(vtkCommand.ErrorEvent, on_error)),
                     (self.gi, self.gi.AddObserver(vtkCommand.WarningEvent, on_warning)),
                     (executive, executive.AddObserver(vtkCommand.ErrorEvent, on_failure))]
        return self

    def __exit__(self, *exc):
        for subject, tag in self.tags:
            subject.RemoveObserver(tag)
        if self.errors and exc[0] is None:
            raise RuntimeError("linkgi: " + "; ".join(self.errors))


def _text(message):
    """VTK's message without its 'ERROR: In file, line N / class (address):' header."""
    return re.sub(r"^.*?\):\s*", "", str(message).strip(), flags=re.S) or str(message)


def _surface(mesh):
    """Any PyVista or VTK dataset as polydata (the filter lights surfaces); a composite
    dataset as it is (the filter lights its blocks as one scene)."""
    mesh = pyvista.wrap(mesh)
    if isinstance(mesh, (vtkPolyData, vtkCompositeDataSet)):
        return mesh
    if not hasattr(mesh, "extract_surface"):
        raise TypeError(f"linkgi: cannot light a {type(mesh).__name__}: give a PyVista mesh "
                        "or VTK dataset")
    return mesh.extract_surface()


def illuminate(mesh, lights, method=None, albedo=None, **settings):
    """Lights `mesh` and returns a new pyvista.PolyData with point arrays DirectIrradiance,
    IndirectIrradiance and Radiance (W/m^2 and W/(m^2 sr), linear RGB) and the solve's
    record in the field data (LinkGI.Method, LinkGI.Ms<Stage>, ...).

    mesh: any PyVista mesh (a non-polydata one is lit on its surface); a MultiBlock is one
        scene (its blocks shadow each other) and comes back as a MultiBlock.
    lights: a pyvista.Plotter (its lights; its light kit's follow its camera), a
        pyvista.Light or vtkLight, or a list of them. A point or spot light falls off as
        its attenuation_values say: (0, 0, 1) is a lamp's 1/r^2, VTK's default none.
    method: the method's name (default "links"); see linkgi.methods().
    albedo: a number or RGB in [0, 1], or the name of a point or cell array (linear RGB).
    settings: bounces=, rays=, vpls=, bins=, photons=, clusters=, gather_rays=, paths=,
        two_sided=, or any filter property in snake case.
    """
    gi = vtkGlobalIlluminationFilter()
    _configure(gi, method, albedo, settings)
    _set_lights(gi, lights)
    gi.SetInputDataObject(_surface(mesh))
    with _Messages(gi):
        gi.Update()
    output = gi.GetOutputDataObject(0)
    lit = output.NewInstance()
    lit.ShallowCopy(output)
    return pyvista.wrap(lit)


def add_mesh(plotter, mesh, method=None, albedo=None, lights=None, solver=None, **kwargs):
    """Adds `mesh` to `plotter` drawn with global illumination and returns the actor.

    One call is one solve: the mesh shadows itself and bounces light onto itself. Parts
    that should shadow each other and exchange light go in as one mesh (`part + floor`);
    a MultiBlock is refused with that advice.

    Every keyword of pyvista.Plotter.add_mesh (color, scalars, cmap, clim, show_edges,
    opacity, scalar_bar_args, ...) works as it does there: PyVista makes the actor, then
    its mapper is replaced by a vtkGlobalIlluminationMapper with the same colouring (lookup
    table, scalar range and mode, array), fed by a vtkGlobalIlluminationFilter. Shadows of
    every light come from the mapper's shadow maps; the bounced light from the filter.

    lights: what lights the bounces: the plotter's lights by default (see illuminate()).
    method: as in illuminate().
    albedo: as in illuminate(); by default light bounces in the colour the surface is
        drawn with (its colour, or its scalars through the colour map), as taken when added.
    solver: a dict of the filter's settings, as illuminate() takes them. A keyword that
        names a filter setting and is not one of Plotter.add_mesh's goes there too
        (bounces=3, two_sided=True, environment_color=(0, 0, 0), ...).
    The filter is `actor.GetMapper().GetInputAlgorithm()`: change its settings and the next
    render updates the light.
    """
    gi = vtkGlobalIlluminationFilter()
    settings = dict(solver or {})
    own = inspect.signature(type(plotter).add_mesh).parameters
    for keyword in list(kwargs):
        if keyword not in own and hasattr(gi, "Set" + _property(keyword)):
            settings[keyword] = kwargs.pop(keyword)
    _configure(gi, method, albedo, settings)
    _set_lights(gi, plotter if lights is None else lights)

    actor = plotter.add_mesh(mesh, **kwargs)
    drawn = actor.GetMapper()
    if isinstance(drawn, vtkCompositePolyDataMapper2):
        plotter.remove_actor(actor)
        raise TypeError("linkgi: add_mesh lights one mesh: merge a MultiBlock's parts into "
                        "one (multi_block.combine().extract_surface(), or a + b) so that they "
                        "shadow each other and light bounces between them")
    mapper = vtkGlobalIlluminationMapper()
    vtkMapper.ShallowCopy(mapper, drawn)  # PyVista's colouring: lookup table, range, array
    surface = _surface(drawn.GetInputDataObject(0, 0))
    if albedo is None:  # light bounces in the colour the surface is drawn with
        surface = vtkGlobalIlluminationDrawnAlbedo().Apply(surface, mapper, actor.GetProperty(),
                                                           gi)
    gi.SetInputDataObject(surface)
    with _Messages(gi):
        gi.Update()  # errors here, not at the first render
    mapper.SetInputConnection(gi.GetOutputPort())
    actor.SetMapper(mapper)
    return actor
