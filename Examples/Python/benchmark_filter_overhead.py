"""The filter's own cost (triangulation, normals, array conversion, output arrays) against
the engine's, for a full and a light-only update of a standard scene.

    PYTHONPATH=build/lib/python3.11/dist-packages /usr/bin/python3 \\
        Examples/Python/benchmark_filter_overhead.py [scene]

Prints one JSON line per update: LinkGI.MsFilter is all of RequestData, LinkGI.MsTotal the
engine's update inside it.
"""
import json
import sys

import linkgi
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401  (vtkLight's factory)
from vtkmodules.vtkRenderingCore import vtkLightCollection

scene = sys.argv[1] if len(sys.argv) > 1 else "tearoom"
source = linkgi.vtkGlobalIlluminationSceneSource()
source.SetSceneName(scene)
lights = vtkLightCollection()
source.CreateLights(lights)
gi = linkgi.vtkGlobalIlluminationFilter()
gi.SetAlbedoArrayName("Albedo")
gi.SetEmissionArrayName("Emission")
gi.SetInputConnection(source.GetOutputPort())
gi.SetBackendToCPU()
lights.InitTraversal()
for _ in range(lights.GetNumberOfItems()):
    gi.AddLight(lights.GetNextItem())
source.Update()  # the scene's generation is not the filter's cost


def stat(name):
    return gi.GetOutput().GetFieldData().GetArray("LinkGI." + name).GetTuple1(0)


for update in ("full", "light only"):
    if update == "light only":
        x, y, z = gi.GetLight(0).GetPosition()
        gi.GetLight(0).SetPosition(x + 0.05, y, z)
    gi.Update()
    request, engine = stat("MsFilter"), stat("MsTotal")
    print(json.dumps({"scene": scene, "update": update, "ms_request_data": round(request, 2),
                      "ms_engine": round(engine, 2), "ms_filter_overhead": round(request - engine, 2),
                      "overhead_percent": round(100 * (request - engine) / request, 2)}))
