"""no-room-agreement.py with photon mapping alone (the other methods did not change).

    PYTHONPATH=build/lib/python3.11/dist-packages:Documentation/scripts /usr/bin/python3 \\
      pm-only.py [--refine] MODEL...
"""
import importlib.util
import sys

spec = importlib.util.spec_from_file_location("nra", "Documentation/scripts/no-room-agreement.py")
nra = importlib.util.module_from_spec(spec)
spec.loader.exec_module(nra)
nra.METHODS = ["photon-mapping"]
nra.main([a for a in sys.argv[1:] if a != "--refine"], "--refine" in sys.argv)
