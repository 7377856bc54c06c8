"""pvbatch --mpi: the Global Illumination representation with the scene split across ranks.

Run as `mpirun -np N pvbatch --mpi TestGlobalIlluminationMPI.py ...` (registered for N = 1
and N = 2 in CMakeLists.txt); the scene and the checks are linkgi_mpi_scene.py's.
"""
from paraview import servermanager

import linkgi_mpi_scene
import linkgi_paraview_testing as t

arguments = t.parse_arguments()
t.load_plugin(arguments.plugin, globals())
ranks = servermanager.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()
print("ranks: %d" % ranks)
linkgi_mpi_scene.run(arguments, ranks)
