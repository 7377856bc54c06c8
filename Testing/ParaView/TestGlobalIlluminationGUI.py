"""Run by the ParaView GUI (`paraview --plugins=LinkGI --script=... --exit`) under Xvfb.

Checks that the plugin loaded in the GUI (its proxies are defined), and that the Cornell
box shows with the Global Illumination representation in the GUI's own render view with a
Light Inspector light. The GUI cannot fail a script, so a failure ends the process with
exit code 1 (os._exit); on success --exit closes the GUI normally.
"""
import os

from paraview import servermanager
from paraview.simple import *  # noqa: F401,F403 (the pvpython way)


def say(message):
    # Straight to the process's stderr: the GUI captures Python's own streams.
    os.write(2, (message + "\n").encode())


def fail(message):
    say("FAILED: " + message)
    os._exit(1)


definitions = servermanager.ActiveConnection.Session.GetSessionProxyManager() \
    .GetProxyDefinitionManager()
for group, name in (("filters", "GlobalIllumination"),
                    ("sources", "GlobalIlluminationScene"),
                    ("representations", "GlobalIlluminationRepresentation")):
    if not definitions.HasDefinition(group, name):
        fail("the GUI did not load the plugin's %s proxy %s" % (group, name))

try:
    box = servermanager.sources.GlobalIlluminationScene(Scene="cornell")
    servermanager.ProxyManager().RegisterProxy("sources", "CornellBox", box)
    view = GetActiveViewOrCreate("RenderView")
    view.UseLight = 0
    light = CreateLight()
    light.Coords = "Scene"
    light.Type = "Positional"
    light.Position = [0.278, 0.4488, 0.2795]
    light.ConeAngle = 90
    view.AdditionalLights = [light]
    display = Show(box, view)
    display.Representation = "Global Illumination"
    Render(view)
    display.SMProxy.UpdatePropertyInformation()
    updates = display.SMProxy.GetProperty("GlobalIlluminationUpdates").GetElement(0)
    lights = display.SMProxy.GetProperty("GlobalIlluminationLights").GetElement(0)
except Exception as error:  # anything: the GUI would only log it
    fail("showing the Cornell box failed: %s" % error)
if updates != 1 or lights != 1:
    fail("the GUI's view ran the filter %d times with %d lights (expected 1 and 1)"
         % (updates, lights))
say("ok: the GUI loaded the plugin and drew the Global Illumination representation")
