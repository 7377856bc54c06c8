"""LinkGI Export (a ParaView macro): the active view as a web page and a glTF file.

Writes the colours the view displays, lit by the Global Illumination representation, to
<name>.html (one self-contained page: opens from disk, no network, no LinkGI needed) and
<name>.glb (Blender, any glTF viewer) in the folder of LINKGI_EXPORT_DIR, or the home
folder, and prints where. The same from pvpython or pvbatch:

    import linkgi   # PYTHONPATH=<plugins>/LinkGI/python
    linkgi.export_html(GetActiveView(), "scene.html")
    linkgi.export_glb(GetActiveView(), "scene.glb")
"""
import os
import sys
import time

from paraview import servermanager
from paraview.simple import GetActiveSource, GetActiveView


def linkgi_python_folder():
    """LinkGI/python beside the loaded LinkGI plugin: `linkgi` for ParaView's VTK."""
    plugins = servermanager.vtkSMProxyManager.GetProxyManager().GetPluginManager()
    information = plugins.GetLocalInformation()
    for i in range(information.GetNumberOfPlugins()):
        if information.GetPluginName(i) == "LinkGI" and information.GetPluginLoaded(i):
            return os.path.join(os.path.dirname(information.GetPluginFileName(i)), "python")
    raise RuntimeError("LinkGI Export: load the LinkGI plugin first (Tools > Manage Plugins)")


folder = linkgi_python_folder()
if folder not in sys.path:
    sys.path.insert(0, folder)
import linkgi  # noqa: E402

source = GetActiveSource()
name = servermanager.ProxyManager().GetProxyName("sources", source) if source else None
stem = os.path.join(os.environ.get("LINKGI_EXPORT_DIR", os.path.expanduser("~")),
                    (name or "LinkGI").replace(" ", "_").replace("/", "_") +
                    time.strftime("-%Y%m%d-%H%M%S"))
view = GetActiveView()
page = linkgi.export_html(view, stem + ".html")
glb = linkgi.export_glb(view, stem + ".glb")
for report in (page, glb):
    print("LinkGI Export: %s (%.1f MB, %d triangles)%s" % (
        report["file"], report["bytes"] / 1e6, report["triangles"],
        "; left out: " + "; ".join(report["left_out"]) if report["left_out"] else ""))
