"""Time and peak host memory of one method lighting a real model in a room, through the
filter, in a process of its own (a process's peak resident set only grows).

    for m in 0 1 2 3; do for model in "bunny-inward.vtp 1" "lucy.vtp 2"; do
      PYTHONPATH=build/lib/python3.11/dist-packages /usr/bin/python3 \\
        Documentation/scripts/real-models-peak-memory.py $model $m; done; done

Arguments: the model's file in Testing/Data/Models, its vertical axis (0, 1, 2) and the
method (the filter's numbering: 0 links, 1 instant radiosity, 2 implicit visibility, 3 photon
mapping). Under `mpirun -np N` each rank lights its piece of the scene (the appended cells
split in N runs of equal length) and prints its own peak and estimate. The room is the one of filters.TestGlobalIlluminationAgreement: twice the model's
height on each side, 2.5 times it high, cells of 0.08 of it, a lamp under the ceiling.
"""
import math
import os
import sys
import time

import linkgi
from vtkmodules.vtkFiltersCore import vtkAppendPolyData, vtkReverseSense
from vtkmodules.vtkFiltersParallel import vtkExtractPolyDataPiece
from vtkmodules.vtkFiltersSources import vtkPlaneSource
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
from vtkmodules.vtkRenderingCore import vtkLight

MODELS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Testing", "Data", "Models")


def resident(key):
    """VmRSS or VmHWM of this process, in bytes."""
    for line in open("/proc/self/status"):
        if line.startswith(key):
            return int(line.split()[1]) * 1024
    return 0


def reversed_surface(data):
    reverse = vtkReverseSense()
    reverse.SetInputData(data)
    reverse.ReverseCellsOn()
    reverse.ReverseNormalsOn()
    reverse.Update()
    return reverse.GetOutput()


def room_faces(lo, hi, cell):
    """The six walls of the box [lo, hi], each facing inside."""
    for axis in range(3):
        u, v = [k for k in range(3) if k != axis]
        for side in (0, 1):
            origin = list(lo)
            origin[axis] = hi[axis] if side else lo[axis]
            p1, p2 = list(origin), list(origin)
            p1[u], p2[v] = hi[u], hi[v]
            plane = vtkPlaneSource()
            plane.SetOrigin(*origin)
            plane.SetPoint1(*p1)
            plane.SetPoint2(*p2)
            plane.SetResolution(math.ceil((hi[u] - lo[u]) / cell), math.ceil((hi[v] - lo[v]) / cell))
            plane.Update()
            inside = 1 if side == 0 else -1
            wall = plane.GetOutput()
            yield wall if plane.GetNormal()[axis] * inside > 0 else reversed_surface(wall)


def main(model, up, method):
    reader = vtkXMLPolyDataReader()
    reader.SetFileName(os.path.join(MODELS, model))
    reader.Update()
    surface = reader.GetOutput()
    if "inward" in model:
        surface = reversed_surface(surface)
    b = surface.GetBounds()
    height = b[2 * up + 1] - b[2 * up]
    centre = [(b[0] + b[1]) / 2, (b[2] + b[3]) / 2, (b[4] + b[5]) / 2]
    lo = [c - 2 * height for c in centre]
    hi = [c + 2 * height for c in centre]
    lo[up], hi[up] = b[2 * up], b[2 * up] + 2.5 * height
    scene = vtkAppendPolyData()
    scene.AddInputData(surface)
    for wall in room_faces(lo, hi, 0.08 * height):
        scene.AddInputData(wall)
    scene.Update()
    controller = mpi_controller()
    rank, ranks = (controller.GetLocalProcessId(), controller.GetNumberOfProcesses()) if controller else (0, 1)
    piece = scene
    if ranks > 1:
        piece = vtkExtractPolyDataPiece()
        piece.SetInputConnection(scene.GetOutputPort())
        piece.UpdatePiece(rank, ranks, 0)

    lamp = vtkLight()
    lamp.SetPositional(True)
    lamp.SetConeAngle(180)
    lamp.SetAttenuationValues(0, 0, 1)
    position = list(centre)
    position[up] = hi[up] - 0.25 * height
    lamp.SetPosition(*position)
    lamp.SetIntensity(height * height)
    gi = linkgi.vtkGlobalIlluminationFilter()
    gi.SetInputData(piece.GetOutput())
    gi.AddLight(lamp)
    gi.SetBackendToCPU()
    gi.SetMethod(method)

    before = resident("VmRSS:")
    start = time.time()
    gi.Update()
    seconds = time.time() - start
    peak = resident("VmHWM:") - before
    estimate = gi.GetOutput().GetFieldData().GetArray("LinkGI.HostBytesEstimated").GetValue(0)
    print("%s method %d%s: %d points, %.2f s, peak %.0f MiB above the start, estimated %.0f MiB (%.2fx)"
          % (model, method, " rank %d of %d" % (rank, ranks) if ranks > 1 else "",
             piece.GetOutput().GetNumberOfPoints(), seconds, peak / 2**20, estimate / 2**20, estimate / peak),
          flush=True)
    if controller:
        controller.Finalize(1)  # mpi4py finalizes MPI


def mpi_controller():
    """Under mpirun, the MPI controller, made global for the filter; None otherwise."""
    if int(os.environ.get("OMPI_COMM_WORLD_SIZE", "1")) < 2:
        return None
    from mpi4py import MPI  # noqa: F401 (initializes MPI before VTK's controller exists)
    from vtkmodules.vtkParallelMPI import vtkMPIController
    from vtkmodules.vtkParallelCore import vtkMultiProcessController
    controller = vtkMPIController()
    controller.Initialize()  # MPI is already initialized (mpi4py)
    vtkMultiProcessController.SetGlobalController(controller)
    return controller


if __name__ == "__main__":
    main(sys.argv[1], int(sys.argv[2]), int(sys.argv[3]))
