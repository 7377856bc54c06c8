import sys, os; sys.path.insert(0,'Documentation/scripts')
import importlib.util, numpy as np
spec=importlib.util.spec_from_file_location('nr','Documentation/scripts/no-room-agreement.py'); nr=importlib.util.module_from_spec(spec); spec.loader.exec_module(nr)
from agreement import rel_rmse, vertex_areas
for path in sys.argv[1:]:
    s=nr.read(path); l=nr.lamp(s)
    os.environ.pop('LINKGI_INTERP_DEPTH',None)
    rd,ri,out,_=nr.solve(s,l,'reference'); w=vertex_areas(out)
    for depth in ('1','3'):
        os.environ['LINKGI_INTERP_DEPTH']=depth
        d,i,_,_=nr.solve(s,l,'reference')
        print(path, 'interp depth', depth, 'total %.1f%% indirect %.1f%% mean %+.1f%%'%(100*rel_rmse(d+i,rd+ri,w),100*rel_rmse(i,ri,w),100*(np.sum(w*i)/np.sum(w*ri)-1)))
