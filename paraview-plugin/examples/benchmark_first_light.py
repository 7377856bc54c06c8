"""pvbatch benchmark: when the Global Illumination representation first draws indirect light,
and when its final solution, after Apply, a new contour value and a light move.

    pvbatch paraview-plugin/examples/benchmark_first_light.py --plugin <LinkGI.so>
        [--extent 64] [--plain] [--continuous] [--output result.json]

(with PYTHONPATH holding ParaView's Python modules, as Testing/ParaView/CMakeLists.txt sets
it). The surface: Wavelet -extent..extent contoured at RTData 160 (extent 64: the 150k-point
surface of the orbit benchmark), view 800x600, the light kit. The GUI's way of drawing: Wait
For Global Illumination = Never, one render for the change, then, as the GUI's watcher does,
the representation's state polled by a 100 ms repeating timer (a tick missed during a render
fires when it returns, as a Qt timer's) and a render whenever it says a solution is ready,
until the final solution of the newest request is drawn (--continuous: a render every 20 ms
instead, as while a user keeps interacting); each render is the view's StillRender, as the
GUI's, not paraview.simple's Render, which renders a script's first frame twice
(StillRender, ResetCamera, StillRender); each update's figures are seconds from the change
(Show for Apply) to the first render that drew a solution of it with indirect light, and to
the one that drew its final solution.

1. Apply: Show, Representation = Global Illumination, Render.
2. A new contour value (161, 162, 163; a new mesh each, as a time step), three times.
3. A light move: with a scene point light instead of the light kit, the light moved.

One Apply per process: what it measures is the first dataset of a ParaView session, so run
the script several times for a median. --plain turns the progressive stages off (Progressive
= 0) for the same protocol. Prints the JSON and writes it to --output if given.
"""
import argparse
import json
import os
import platform
import subprocess
import sys
import time

from paraview.simple import *  # noqa: F401,F403 (the pvbatch idiom)

parser = argparse.ArgumentParser()
parser.add_argument("--plugin", required=True)
parser.add_argument("--extent", type=int, default=64)
parser.add_argument("--plain", action="store_true", help="progressive stages off")
parser.add_argument("--continuous", action="store_true",
                    help="render every 20 ms, not only when a solution is ready")
parser.add_argument("--output")
arguments = parser.parse_args(sys.argv[1:])
LoadPlugin(arguments.plugin, remote=False, ns=globals())


def information(display, name):
    # This property only: updating all of them would compute every statistic each poll.
    prop = display.SMProxy.GetProperty("GlobalIllumination" + name)
    display.SMProxy.UpdatePropertyInformation(prop)
    return prop.GetElement(0)


READY = 2  # vtkGlobalIlluminationRepresentation::READY: a newer solution waits to be drawn


def until_final(view, display, start, timeout=600.0):
    """Renders as the GUI does until the newest request's final solution is drawn: once for
    the change, then whenever the state its watcher polls says a solution is ready (with
    --continuous, every 20 ms). Returns the seconds since `start` of the first and of the
    final solution drawn, and the stages."""
    first = None
    render = True
    interval = 0.02 if arguments.continuous else 0.1
    tick = time.perf_counter()
    while time.perf_counter() - start < timeout:
        if render:
            view.StillRender()  # as the GUI renders; see the module's docstring
        request = information(display, "NewestRequest")
        if information(display, "ShownRequest") == request:
            now = time.perf_counter() - start
            stage, stages = information(display, "ShownStage"), information(display, "ShownStages")
            first = now if first is None else first
            if stage == stages:
                return {"first_s": round(first, 3), "final_s": round(now, 3), "stages": stages}
        # A repeating timer, as the GUI's: a tick that fell during a render fires when it
        # returns (once, as a Qt timer does), the others on time.
        tick += interval
        if tick > time.perf_counter():
            time.sleep(tick - time.perf_counter())
        else:
            tick = time.perf_counter()
        render = arguments.continuous or information(display, "State") == READY
    raise RuntimeError("no final solution within %g s" % timeout)


def commit():
    try:
        return subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True,
                              text=True, cwd=os.path.dirname(os.path.abspath(__file__))).stdout.strip()
    except OSError:
        return ""


view = CreateView("RenderView")
view.ViewSize = [800, 600]
extent = arguments.extent
wavelet = Wavelet(WholeExtent=[-extent, extent] * 3)
contour = Contour(Input=wavelet, ContourBy=["POINTS", "RTData"], Isosurfaces=[160.0])
contour.UpdatePipeline()
result = {"benchmark": "paraview-plugin/examples/benchmark_first_light.py",
          "date": time.strftime("%Y-%m-%d"), "commit": commit(),
          "machine": {"cpu": platform.processor() or platform.machine(), "cores": os.cpu_count(),
                      "load_average": os.getloadavg()},
          "points": contour.GetDataInformation().GetNumberOfPoints(),
          "progressive": not arguments.plain, "continuous": arguments.continuous}

start = time.perf_counter()
display = Show(contour, view)
display.Representation = "Global Illumination"
display.GlobalIlluminationWait = "Never"
display.GlobalIlluminationProgressive = 0 if arguments.plain else 1
view.ResetCamera()
result["apply"] = until_final(view, display, start)

result["contour"] = []
for value in (161.0, 162.0, 163.0):
    start = time.perf_counter()
    contour.Isosurfaces = [value]
    result["contour"].append(until_final(view, display, start))

lamp = CreateLight()
lamp.Coords = "Scene"
lamp.Type = "Positional"
lamp.ConeAngle = 180
lamp.Position = [extent * 0.5, extent * 2.0, extent * 1.5]
lamp.Intensity = float(extent * extent * 2)
view.UseLight = 0
view.AdditionalLights = [lamp]
until_final(view, display, time.perf_counter())
start = time.perf_counter()
lamp.Position = [-extent * 0.5, extent * 2.0, extent * 1.5]
result["light"] = until_final(view, display, start)
result["machine"]["load_average_after"] = os.getloadavg()

text = json.dumps(result, indent=2)
print(text)
if arguments.output:
    with open(arguments.output, "w") as out:
        out.write(text + "\n")
sys.stdout.flush()
os._exit(0)  # skip pvbatch's teardown of live proxies
