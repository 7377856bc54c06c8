"""Benchmark of the shadow casters' exchange under MPI: what
vtkGlobalIlluminationGlobalCasters.Gather costs per geometry change, per render without a
change, and with decimated proxies past its limit.

    mpirun -np P /usr/bin/python3 Examples/Python/benchmark_global_casters.py \
        [--triangles 2000000] [--repeats 5] [--output result.json]

(PYTHONPATH=<build>/lib/python3.11/dist-packages, as the README says). Every rank holds
triangles/P triangles: a square of its own, one above the other. A repeat moves every
rank's points (a geometry change) and times, on every rank, after a barrier:

- `exchange_s`: the Gather that exchanges the triangles (36 bytes each);
- `unchanged_s`: the next Gather, which only reduces a flag;
- `proxy_s`: a Gather with MaximumTriangles at a tenth of the others' triangles, so that
  every rank clusters its own into a proxy first (vtkQuadricClustering).

Rank 0 writes the medians, minimum and maximum over the repeats of the slowest rank, the
bytes it received and every rank's peak resident memory as JSON.
"""
import argparse
import json
import os
import platform
import resource
import statistics
import sys
import time

from mpi4py import MPI  # noqa: F401 (initializes MPI before VTK's controller exists)
from vtkmodules.vtkCommonCore import vtkDoubleArray
from vtkmodules.vtkFiltersCore import vtkTriangleFilter
from vtkmodules.vtkFiltersSources import vtkPlaneSource
from vtkmodules.vtkParallelCore import vtkCommunicator, vtkMultiProcessController
from vtkmodules.vtkParallelMPI import vtkMPIController

from linkgi.LinkGIRenderingGlobalIllumination import vtkGlobalIlluminationGlobalCasters

parser = argparse.ArgumentParser()
parser.add_argument("--triangles", type=int, default=2000000, help="over all ranks")
parser.add_argument("--repeats", type=int, default=5)
parser.add_argument("--output")
arguments = parser.parse_args(sys.argv[1:])

controller = vtkMPIController()
controller.Initialize()  # MPI is already initialized (mpi4py)
vtkMultiProcessController.SetGlobalController(controller)
rank = controller.GetLocalProcessId()
ranks = controller.GetNumberOfProcesses()

# triangles/P triangles: 2 n^2 of a square at height `rank`.
n = max(1, int(round((arguments.triangles / ranks / 2) ** 0.5)))
plane = vtkPlaneSource()
plane.SetOrigin(0, 0, rank)
plane.SetPoint1(1, 0, rank)
plane.SetPoint2(0, 1, rank)
plane.SetResolution(n, n)
triangles = vtkTriangleFilter()
triangles.SetInputConnection(plane.GetOutputPort())
triangles.Update()
mine = triangles.GetOutput()
others = (ranks - 1) * mine.GetNumberOfPolys()

casters = vtkGlobalIlluminationGlobalCasters()


def _one(value):
    a = vtkDoubleArray()
    a.SetNumberOfTuples(1)
    a.SetValue(0, value)
    return a


def slowest_time(work):
    controller.Barrier()
    started = time.perf_counter()
    work()
    elapsed = time.perf_counter() - started
    result = vtkDoubleArray()
    controller.AllReduce(_one(elapsed), result, vtkCommunicator.MAX_OP)
    return result.GetValue(0)


def move():
    points = mine.GetPoints()
    x, y, z = points.GetPoint(0)
    points.SetPoint(0, x, y, z + 1e-6)
    points.Modified()


runs = {"exchange_s": [], "unchanged_s": [], "proxy_s": []}
received = {}
for repeat in range(arguments.repeats):
    casters.SetMaximumTriangles(20000000)
    move()
    runs["exchange_s"].append(slowest_time(lambda: casters.Gather(mine)))
    received["exchange"] = (casters.GetNumberOfTriangles(), casters.GetLastGatherBytes())
    runs["unchanged_s"].append(slowest_time(lambda: casters.Gather(mine)))
    casters.SetMaximumTriangles(max(1, others // 10))
    move()
    runs["proxy_s"].append(slowest_time(lambda: casters.Gather(mine)))
    received["proxy"] = (casters.GetNumberOfTriangles(), casters.GetLastGatherBytes())

peak = _one(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0)
peaks = vtkDoubleArray()
controller.AllGather(peak, peaks)
if rank == 0:
    result = {
        "benchmark": "benchmark_global_casters.py",
        "machine": {"cores": os.cpu_count(), "host": platform.node(),
                    "loadavg_1min": os.getloadavg()[0]},
        "ranks": ranks,
        "triangles_per_rank": mine.GetNumberOfPolys(),
        "rank0_received_triangles": received["exchange"][0],
        "rank0_received_bytes": received["exchange"][1],
        "rank0_proxy_triangles": received["proxy"][0],
        "rank0_proxy_bytes": received["proxy"][1],
        "maxrss_mb": [peaks.GetValue(i) for i in range(ranks)],
    }
    for key, values in runs.items():
        result[key] = {"median": statistics.median(values), "min": min(values),
                       "max": max(values), "runs": values}
    result["exchange_gb_per_s"] = received["exchange"][1] / result["exchange_s"]["median"] / 1e9
    text = json.dumps(result, indent=1)
    print(text)
    if arguments.output:
        with open(arguments.output, "w") as f:
            f.write(text + "\n")
controller.Finalize(1)  # mpi4py finalizes MPI
