"""pvbatch with the installed plugin, found by name: run with PV_PLUGIN_CONFIG_FILE set to the
installed plugin list (<prefix>/<libdir>/paraview-5.11/plugins/LinkGI.xml), ParaView reads
the name LinkGI there, finds LinkGI/LinkGI.so beside the list and loads it before the script
starts. Checks that the plugin ParaView knows as LinkGI is that file, and that its source and
filter proxies work: the Cornell box under the Global Illumination filter's point light is
lit, directly and by bounced light.

Usage: PV_PLUGIN_CONFIG_FILE=<LinkGI.xml> pvbatch CheckInstalledPlugin.py <prefix>
"""
import os
import sys

from paraview import servermanager
from paraview.simple import *  # noqa: F401,F403 (the pvpython way)

prefix = os.path.realpath(sys.argv[1])


def check(condition, message):
    if not condition:
        print("FAILED: " + message)
        sys.stdout.flush()
        os._exit(1)  # skip pvbatch's teardown, which would bury the message
    print("ok: " + message)


config = os.environ.get("PV_PLUGIN_CONFIG_FILE", "")
check(os.path.realpath(config).startswith(prefix + os.sep), "the plugin list %s" % config)
plugins = servermanager.vtkSMProxyManager.GetProxyManager().GetPluginManager().GetLocalInformation()
found = {plugins.GetPluginName(i): (plugins.GetPluginFileName(i), plugins.GetPluginLoaded(i))
         for i in range(plugins.GetNumberOfPlugins())}
check("LinkGI" in found, "ParaView knows a plugin named LinkGI (%s)" % sorted(found))
path, loaded = found["LinkGI"]
check(loaded and os.path.realpath(path) == os.path.join(os.path.dirname(os.path.realpath(config)),
                                                        "LinkGI", "LinkGI.so"),
      "LinkGI loaded from %s" % path)

box = GlobalIlluminationScene(Scene="cornell")
gi = GlobalIllumination(Input=box)
gi.LightType = "Point"
gi.LightPosition = [0.278, 0.449, 0.280]
gi.RaysPerVertex = "64"
gi.UpdatePipeline()
out = servermanager.Fetch(gi)
for name in ("DirectIrradiance", "IndirectIrradiance", "Radiance"):
    array = out.GetPointData().GetArray(name)
    check(array is not None and array.GetNumberOfTuples() == out.GetNumberOfPoints()
          and array.GetRange(0)[1] > 0, "point array %s, lit" % name)
os._exit(0)
