"""Every file through the filter with default settings and a lamp: what a new user sees."""
import sys, time, math
import numpy as np
import linkgi
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
from vtkmodules.vtkIOPLY import vtkPLYReader
from vtkmodules.vtkIOGeometry import vtkSTLReader, vtkOBJReader, vtkBYUReader
from vtkmodules.vtkIOLegacy import vtkDataSetReader
from vtkmodules.vtkFiltersGeometry import vtkDataSetSurfaceFilter
from vtkmodules.vtkRenderingCore import vtkLight

def read(path):
    ext = path.rsplit(".", 1)[1].lower()
    r = {"vtp": vtkXMLPolyDataReader, "ply": vtkPLYReader, "stl": vtkSTLReader, "obj": vtkOBJReader,
         "g": vtkBYUReader, "vtk": vtkDataSetReader}[ext]()
    if ext == "g":
        r.SetGeometryFileName(path)
    else:
        r.SetFileName(path)
    s = vtkDataSetSurfaceFilter()
    s.SetInputConnection(r.GetOutputPort())
    s.Update()
    return s.GetOutput()

import os
METHODS = os.environ.get("METHODS", "links").split(",")
for path in sys.argv[1:]:
    surf = read(path)
    b = surf.GetBounds()
    c = [(b[0] + b[1]) / 2, (b[2] + b[3]) / 2, (b[4] + b[5]) / 2]
    d = math.sqrt((b[1] - b[0]) ** 2 + (b[3] - b[2]) ** 2 + (b[5] - b[4]) ** 2)
    for method in METHODS:
        light = vtkLight()
        light.SetPositional(True)
        light.SetConeAngle(180)
        light.SetPosition(c[0] + 0.6 * d, c[1] + 0.8 * d, c[2] + 1.0 * d)
        light.SetFocalPoint(*c)
        gi = linkgi.vtkGlobalIlluminationFilter()
        gi.SetInputData(surf)
        gi.AddLight(light)
        gi.SetBackendToCPU()
        gi.SetMethod(linkgi.methods()[method])
        t = time.perf_counter()
        try:
            gi.Update()
        except Exception as e:
            print("%-40s EXCEPTION %s" % (path, e)); continue
        t = time.perf_counter() - t
        out = gi.GetOutput()
        n = out.GetNumberOfPoints()
        w = out.GetFieldData().GetAbstractArray("LinkGI.Warnings")
        warns = [w.GetValue(i) for i in range(w.GetNumberOfValues())] if w else []
        if n == 0:
            print("%-40s %d pts in, 0 out; %s" % (path, surf.GetNumberOfPoints(), warns)); continue
        dr = vtk_to_numpy(out.GetPointData().GetArray("DirectIrradiance")).sum(1)
        ind = vtk_to_numpy(out.GetPointData().GetArray("IndirectIrradiance")).sum(1)
        bad = np.count_nonzero(~np.isfinite(dr)) + np.count_nonzero(~np.isfinite(ind))
        print("%-32s %7d pts %7d cells %6.2fs lit %5.1f%% ind>0 %5.1f%% nan %d extent %.3g warn %d" % (
            path.split("/")[-1][:14] + " " + method[:10], n, out.GetNumberOfCells(), t, 100 * np.mean(dr > 0), 100 * np.mean(ind > 0), bad, d, len(warns)))
        for x in warns:
            print("    -", x[:300])
