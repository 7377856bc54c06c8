import sys, importlib.util, time
sys.path.insert(0, "/work/main/Documentation/scripts")
spec = importlib.util.spec_from_file_location("nra", "/work/main/Documentation/scripts/no-room-agreement.py")
nra = importlib.util.module_from_spec(spec); spec.loader.exec_module(nra)
import linkgi
surface = nra.read(sys.argv[1]); light = nra.lamp(surface)
gi=linkgi.vtkGlobalIlluminationFilter(); gi.SetInputData(surface); gi.AddLight(light); gi.SetBackendToCPU()
gi.SetMethod(linkgi.methods()['implicit-visibility'])
ts=[]
for k in range(3):
    gi.Modified(); surface.Modified()
    t=time.time(); gi.Update(); ts.append(time.time()-t)
fd=gi.GetOutput().GetFieldData()
vals={fd.GetArrayName(i): fd.GetArray(i).GetValue(0) for i in range(fd.GetNumberOfArrays()) if fd.GetArray(i) and fd.GetArray(i).GetNumberOfTuples()==1 and 'Link' in (fd.GetArrayName(i) or '')}
print(sys.argv[1].split('/')[-1], vals, ["%.2f"%t for t in ts])
