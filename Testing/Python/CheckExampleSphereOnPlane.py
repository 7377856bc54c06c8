"""Runs Examples/Python/sphere_on_plane.py and checks that the file it writes holds a lit
scene: the three point arrays, positive direct and indirect light.

Usage: CheckExampleSphereOnPlane.py <example script> <output .vtp>
"""
import subprocess
import sys

from vtkmodules.vtkIOXML import vtkXMLPolyDataReader

example, output = sys.argv[1], sys.argv[2]
subprocess.run([sys.executable, example, output], check=True)
reader = vtkXMLPolyDataReader()
reader.SetFileName(output)
reader.Update()
pd = reader.GetOutput().GetPointData()
for name in ("DirectIrradiance", "IndirectIrradiance", "Radiance"):
    array = pd.GetArray(name)
    assert array is not None, name
    assert array.GetNumberOfTuples() == reader.GetOutput().GetNumberOfPoints(), name
    assert array.GetRange(0)[1] > 0, name
print("ok")
