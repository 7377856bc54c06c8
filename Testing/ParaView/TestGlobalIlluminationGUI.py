"""Run by the ParaView GUI (`paraview --plugins=LinkGI --script=... --exit`) under Xvfb.

Checks that the plugin loaded in the GUI (its proxies are defined), and that the Cornell
box shows with the Global Illumination representation in the GUI's own render view with a
Light Inspector light. The GUI cannot fail a script, so a failure ends the process with
exit code 1 (os._exit).

The GUI never waits for global illumination: the script's Render returns before the first
solution (a sphere over a floor at 1024 rays per vertex, whose links take seconds), and the
script ends with the solution still pending. The GUI's event loop then runs, and the
representation's watcher, on a timer of the view's interactor, must render the view by
itself once the solution is ready: an observer of the interactor's timer ticks ends the
process with 0 when the drawn solution is the newest request's, with 1 after 3000 ticks.
So the test runs without --exit. Then the Macros menu's LinkGIExport, found in
PV_MACRO_PATH as the GUI finds it, exports the drawn solution as a page and a glTF file.
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
    display.GlobalIlluminationWait = "Always"
    Render(view)
    display.SMProxy.UpdatePropertyInformation()
    updates = display.SMProxy.GetProperty("GlobalIlluminationUpdates").GetElement(0)
    lights = display.SMProxy.GetProperty("GlobalIlluminationLights").GetElement(0)
except Exception as error:  # anything: the GUI would only log it
    fail("showing the Cornell box failed: %s" % error)
if updates != 1 or lights != 1:
    fail("the GUI's view drew %d solutions with %d lights (expected 1 and 1)"
         % (updates, lights))
say("ok: the GUI loaded the plugin and drew the Global Illumination representation")


def information(display, name):
    return display.SMProxy.GetProperty("GlobalIllumination" + name).GetElement(0)


try:
    Hide(box, view)
    sphere = Sphere(Center=[0, 0.8, 0], Radius=0.5, ThetaResolution=160, PhiResolution=160)
    floor = Plane(Origin=[-2, 0, -2], Point1=[-2, 0, 2], Point2=[2, 0, -2], XResolution=60,
                  YResolution=60)
    scene = AppendGeometry(Input=[sphere, floor])
    gi = Show(scene, view)
    gi.Representation = "Global Illumination"
    gi.GlobalIlluminationRays = 1024
    Render(view)
    gi.SMProxy.UpdatePropertyInformation()
    pending = (information(gi, "Updates"), information(gi, "NewestRequest"))
    interactor = view.GetRenderWindow().GetInteractor()
except Exception as error:
    fail("showing the sphere failed: %s" % error)
if gi.GlobalIlluminationWait != "In Scripts" or pending != (0, 1):
    fail("the GUI's render waited (Wait %s; solutions drawn, newest request: %s)"
         % (gi.GlobalIlluminationWait, pending))
say("ok: the GUI's render returned before the first solution")

ticks = [0]


def export_with_the_macro():
    """The Macros menu's LinkGIExport, found where the GUI finds macros (PV_MACRO_PATH),
    run in the GUI's Python on the drawn solution: it writes a page and a glTF file."""
    folders = [f for f in os.environ.get("PV_MACRO_PATH", "").split(os.pathsep) if f]
    macros = [os.path.join(f, "LinkGIExport.py") for f in folders
              if os.path.exists(os.path.join(f, "LinkGIExport.py"))]
    if not macros:
        fail("no LinkGIExport macro in PV_MACRO_PATH (%s)" % folders)
    out = os.environ["LINKGI_EXPORT_DIR"]
    os.makedirs(out, exist_ok=True)
    before = set(os.listdir(out))
    try:
        with open(macros[0]) as f:
            exec(compile(f.read(), macros[0], "exec"), {"__name__": "__main__"})
    except Exception as error:
        fail("the LinkGIExport macro failed in the GUI: %s" % error)
    written = sorted(set(os.listdir(out)) - before)
    if not any(w.endswith(".html") for w in written) or not any(w.endswith(".glb") for w in written):
        fail("the LinkGIExport macro wrote %s" % written)
    say("ok: the GUI's LinkGIExport macro wrote %s" % written)


def on_tick(caller, event):
    ticks[0] += 1
    gi.SMProxy.UpdatePropertyInformation()
    if information(gi, "Updates") == 1 and information(gi, "ShownRequest") == 1:
        say("ok: the watcher rendered the solution when it was ready (after %d ticks)"
            % ticks[0])
        export_with_the_macro()
        os._exit(0)
    if ticks[0] >= 3000:
        fail("no render showed the solution after %d timer ticks" % ticks[0])


interactor.AddObserver("TimerEvent", on_tick)
