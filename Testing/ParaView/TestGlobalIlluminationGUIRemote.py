"""Run by the ParaView GUI connected to a pvserver that renders (TestGlobalIlluminationPVServer.py
--gui starts both) under Xvfb: the GUI's watcher must draw a new solution of the server by
itself, as it does without a server (TestGlobalIlluminationGUI.py).

The state it polls, GlobalIlluminationState, is gathered from the server's representation
(the client's own copy has no data when the server renders). The server learns that its
client is the GUI at the watcher's first poll, so the first render waits there; after a
change (more rays: new links, seconds of work) the script renders once and only watches:
the state must go from solving (1) through ready (2) to idle (0), and only a render by the
watcher can make it idle. A failure ends the process with exit code 1 (os._exit), success
with 0; the GUI cannot fail a script otherwise.
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


try:
    if not servermanager.ActiveConnection.IsRemote():
        fail("the GUI is not connected to a server")
    GetSettingsProxy("RenderViewSettings").RemoteRenderThreshold = 0  # the server renders
    view = GetActiveViewOrCreate("RenderView")
    sphere = Sphere(Center=[0, 0.8, 0], Radius=0.5, ThetaResolution=160, PhiResolution=160)
    floor = Plane(Origin=[-2, 0, -2], Point1=[-2, 0, 2], Point2=[2, 0, -2], XResolution=60,
                  YResolution=60)
    gi = Show(AppendGeometry(Input=[sphere, floor]), view)
    gi.Representation = "Global Illumination"
    gi.GlobalIlluminationRays = 256
    Render(view)
    interactor = view.GetRenderWindow().GetInteractor()
except Exception as error:  # anything: the GUI would only log it
    fail("showing the sphere failed: %s" % error)


def state():
    gi.SMProxy.UpdatePropertyInformation()
    return gi.SMProxy.GetProperty("GlobalIlluminationState").GetElement(0)


ticks = [0]
seen = []


def on_tick(caller, event):
    ticks[0] += 1
    if ticks[0] < 20:
        return  # the watcher's first polls tell the server that its client is the GUI
    if ticks[0] == 20:
        gi.GlobalIlluminationRays = 1024
        Render(view)
        say("ok: rays changed and rendered at tick 20")
        return
    now = state()
    if not seen or now != seen[-1]:
        seen.append(now)
    if seen[0] == 0:
        fail("the render after the change waited, or the server's state did not reach the "
             "client (state 0 at once)")
    if now == 0:
        say("ok: the watcher drew the server's solution (states %s, tick %d)" % (seen, ticks[0]))
        os._exit(0)
    if ticks[0] >= 3000:
        fail("no render showed the server's solution after %d ticks (states %s)"
             % (ticks[0], seen))


interactor.AddObserver("TimerEvent", on_tick)
interactor.CreateRepeatingTimer(100)  # ticks of its own: the watcher's stop when it is idle
