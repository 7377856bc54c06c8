"""LinkGI: per-vertex multi-bounce global illumination for VTK.

    import linkgi
    gi = linkgi.vtkGlobalIlluminationFilter()
"""
from vtkmodules import vtkCommonExecutionModel as _  # noqa: F401  (base classes first)

from .LinkGIFiltersGlobalIllumination import *  # noqa: F401,F403
