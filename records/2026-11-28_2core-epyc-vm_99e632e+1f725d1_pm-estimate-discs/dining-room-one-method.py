"""One method's update in the dining room against the reference of dining-room-agreement.py
(cached in /tmp/dr/ref.npz): PYTHONPATH=build/lib/python3.11/dist-packages /usr/bin/python3
THIS.py METHOD... with the scene at /tmp/dr/dining-room.vtp (dining-room-scene.py)."""
import sys, os, importlib.util
import numpy as np
sys.path.insert(0, "/work/main/Documentation/scripts")  # agreement.py
spec = importlib.util.spec_from_file_location("dra", "/work/main/Documentation/scripts/dining-room-agreement.py")
dra = importlib.util.module_from_spec(spec); spec.loader.exec_module(dra)
surface = dra.read("/tmp/dr/dining-room.vtp")
areas = dra.vertex_areas(surface)
part = dra.vtk_to_numpy(surface.GetPointData().GetArray("Part"))
if not os.path.exists("/tmp/dr/ref.npz"):
    d0, i0, _, _ = dra.solve(surface, "reference", 1024, 0)
    d1, i1, _, _ = dra.solve(surface, "reference", 1024, 1)
    np.savez("/tmp/dr/ref.npz", d=d0, i=(i0 + i1) / 2)
r = np.load("/tmp/dr/ref.npz"); rd, ri = r["d"], r["i"]
rest = part != dra.SHADE
for method in sys.argv[1:]:
    d, i, t, out = dra.solve(surface, method)
    print("%s: total %.1f%% aside %.1f%% ind %.1f%% aside %.1f%% bias %+.1f%% aside %+.1f%% %.2f s" % (method,
        100*dra.rel_rmse(d+i, rd+ri, areas), 100*dra.rel_rmse((d+i)[rest], (rd+ri)[rest], areas[rest]),
        100*dra.rel_rmse(i, ri, areas), 100*dra.rel_rmse(i[rest], ri[rest], areas[rest]),
        100*(np.sum(areas*i)/np.sum(areas*ri)-1), 100*(np.sum((areas*i)[rest])/np.sum((areas*ri)[rest])-1), t))
    np.save("/tmp/dr/%s.npy" % method, np.stack([d, i]))
