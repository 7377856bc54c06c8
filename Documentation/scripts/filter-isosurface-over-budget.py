"""A ~4M-point isosurface through vtkGlobalIlluminationFilter with default settings:
the memory budget must light it through a proxy instead of the process being killed.

    /usr/bin/time -v env PYTHONPATH=build/lib/python3.11/dist-packages /usr/bin/python3 \
      Documentation/scripts/filter-isosurface-over-budget.py 350

The argument is the extent E of vtkRTAnalyticSource (-E..E, contoured at 160; 350: 4.1M
points). Record: records/2026-11-23_2core-epyc-vm_28b2fde_filter-isosurface4m."""
import sys, time
import linkgi
from vtkmodules.vtkImagingCore import vtkRTAnalyticSource
from vtkmodules.vtkFiltersCore import vtkFlyingEdges3D
from vtkmodules.vtkRenderingCore import vtkLight
extent = int(sys.argv[1]) if len(sys.argv) > 1 else 350
source = vtkRTAnalyticSource()
source.SetWholeExtent(-extent, extent, -extent, extent, -extent, extent)
contour = vtkFlyingEdges3D()
contour.SetInputConnection(source.GetOutputPort())
contour.SetValue(0, 160.0)
contour.ComputeNormalsOn()
t = time.perf_counter()
contour.Update()
surface = contour.GetOutput()
print("isosurface: %d points, %d triangles, %.1f s" % (surface.GetNumberOfPoints(), surface.GetNumberOfCells(), time.perf_counter() - t), flush=True)
source = None
light = vtkLight()
light.SetPositional(True)
light.SetConeAngle(180)
light.SetPosition(0, 2.0 * extent, 0)
light.SetIntensity(4.0 * extent * extent)
gi = linkgi.vtkGlobalIlluminationFilter()
gi.SetInputData(surface)
gi.AddLight(light)
gi.SetBackendToCPU()
t = time.perf_counter()
gi.Update()
out = gi.GetOutput()
fd = out.GetFieldData()
warnings = fd.GetAbstractArray("LinkGI.Warnings")
print("filter: %.1f s, %d points lit" % (time.perf_counter() - t, out.GetNumberOfPoints()))
for i in range(warnings.GetNumberOfValues() if warnings else 0):
    print("warning:", warnings.GetValue(i))
for name in ("MsTotal", "Elements", "MsDecimate", "MsTransfer"):
    a = fd.GetArray("LinkGI." + name)
    print(name, a.GetTuple1(0) if a else None)
d = out.GetPointData().GetArray("IndirectIrradiance")
print("indirect range", d.GetRange(0) if d else None)
