"""LinkGI: per-vertex multi-bounce global illumination for VTK.

    import linkgi
    from vtkmodules.vtkRenderingCore import vtkLight

    gi = linkgi.vtkGlobalIlluminationFilter()
    gi.SetInputConnection(source.GetOutputPort())
    gi.AddLight(vtkLight())
    gi.Update()  # point arrays DirectIrradiance, IndirectIrradiance, Radiance

Needs Debian's /usr/bin/python3 (the one with VTK 9.1). Installed (`cmake --install`, or the
linkgi .deb) it needs nothing else; from a build tree, PYTHONPATH=<build>/lib/python3.11/dist-packages.
For ParaView's Python (pvpython, pvbatch) the plugin's LinkGI/python folder holds the same
package built against ParaView's VTK.

PyVista: linkgi.pyvista.add_mesh(plotter, mesh, ...) and linkgi.pyvista.illuminate(mesh,
lights, ...).

Sharing (numpy needed): linkgi.export_html and linkgi.export_glb write what the global
illumination mappers display as a web page or glTF; python -m linkgi.web FILE lights a model
live in the browser (trame).
"""
# The wrapped classes derive from and take VTK classes of these modules: load them first.
from vtkmodules import vtkCommonCore as _core  # noqa: F401
from vtkmodules import vtkCommonDataModel as _data  # noqa: F401
from vtkmodules import vtkCommonExecutionModel as _exec  # noqa: F401
from vtkmodules import vtkRenderingCore as _rendering  # noqa: F401

from .LinkGIFiltersGlobalIllumination import *  # noqa: F401,F403
from .LinkGIRenderingGlobalIllumination import *  # noqa: F401,F403


def methods():
    """The solution methods by the names the output's LinkGI.Method gives them ("links",
    "instant-radiosity", ...), each with the value vtkGlobalIlluminationFilter.SetMethod
    takes, in that value's order: read from the filter's SetMethodTo... functions."""
    gi = vtkGlobalIlluminationFilter()  # noqa: F405 (from the wrapped module above)
    names = {}
    for attribute in dir(gi):
        if attribute.startswith("SetMethodTo"):
            getattr(gi, attribute)()
            names[gi.GetMethodAsString()] = gi.GetMethod()
    return dict(sorted(names.items(), key=lambda item: item[1]))


def __getattr__(name):
    # The exporters need numpy: imported on first use, not with the package.
    if name in ("export_html", "export_glb", "bake"):
        from . import export
        return getattr(export, name)
    raise AttributeError(f"module 'linkgi' has no attribute '{name}'")
