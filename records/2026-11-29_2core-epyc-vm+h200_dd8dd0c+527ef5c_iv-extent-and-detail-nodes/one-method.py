import sys, importlib.util, numpy as np
sys.path.insert(0, "/work/main/Documentation/scripts")
spec = importlib.util.spec_from_file_location("nra", "/work/main/Documentation/scripts/no-room-agreement.py")
nra = importlib.util.module_from_spec(spec); spec.loader.exec_module(nra)
surface = nra.read(sys.argv[1]); light = nra.lamp(surface)
rd, ri, out, _ = nra.solve(surface, light, "reference")
w = nra.vertex_areas(out)
for method in sys.argv[2:]:
    d, i, _, sec = nra.solve(surface, light, method)
    print(method, "total %.1f%% ind %.1f%% bias %+.1f%% %.2f s" % (100*nra.rel_rmse(d+i, rd+ri, w), 100*nra.rel_rmse(i, ri, w), 100*(np.sum(w*i)/np.sum(w*ri)-1), sec), flush=True)
