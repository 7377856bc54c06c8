"""pvbatch --mpi: the Global Illumination representation and filter with the scene split
across ranks.

Run as `mpirun -np N pvbatch --mpi TestGlobalIlluminationMPI.py ... [--write-arrays F |
--reference-arrays F]` (registered for N = 1, 2 and 3 in CMakeLists.txt: the one-rank run
writes the filter's arrays, the others compare theirs); the scene and the checks are
linkgi_mpi_scene.py's.
"""
import argparse
import sys

from paraview import servermanager

import linkgi_mpi_scene
import linkgi_paraview_testing as t

parser = argparse.ArgumentParser()
parser.add_argument("--plugin", required=True, help="the LinkGI plugin library")
parser.add_argument("--baseline-dir", required=True)
parser.add_argument("--output-dir", required=True)
parser.add_argument("--write-arrays", help="write the filter's output here (one rank)")
parser.add_argument("--reference-arrays", help="compare the filter's output with this file")
arguments = parser.parse_args(sys.argv[1:])
t.load_plugin(arguments.plugin, globals())
ranks = servermanager.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()
print("ranks: %d" % ranks)
linkgi_mpi_scene.run(arguments, ranks)
linkgi_mpi_scene.check_arrays(arguments, ranks, globals(), write=arguments.write_arrays,
                              reference=arguments.reference_arrays)
