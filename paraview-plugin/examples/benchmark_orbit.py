"""pvbatch benchmark of the Global Illumination representation: ms per orbit frame.

    pvbatch paraview-plugin/examples/benchmark_orbit.py --plugin <LinkGI.so> [--repeats 5]
        [--output result.json]

(with PYTHONPATH holding ParaView's Python modules, as Testing/ParaView/CMakeLists.txt sets
it). Datasets: Wavelet -40..40 contoured at RTData 160 (a 54k-point surface) and
Wavelet -64..64 at 160 (a larger one, >= 120k points). View 800x600, default view lights
(the light kit), 10 orbit steps of 5 degrees (Azimuth) per run, each step one Render();
a run's figure is its mean ms per frame, and the table gives the median, minimum and
maximum of `--repeats` runs, and `cpu_ms_per_frame` the median CPU time per frame of the
process's thread groups (the render thread, llvmpipe's, the background solve's; Linux).
With --count-solutions, background rows also give `new_solutions_per_orbit`: per run, the
frames that drew a newer solution than the frame before (read between the timed frames,
which gives the worker those moments too: leave it off for the timing figures).
Rows:

- Surface;
- Global Illumination, key light not bounced, no shadows;
- ... key light not bounced, shadows;
- ... key light bounced (the default), shadows;
- ... light kit off and one static scene point light, shadows.

Each Global Illumination row starts from a finished solution (the first render waits).
With a plugin that solves in the background, orbit frames then do not wait (Wait For
Global Illumination = Never, as the GUI renders); the key-light-bounced row is also
measured with the scripts' default (In Scripts: every frame waits for its solution). With
an older plugin (no such property) every frame solves synchronously.

`apply_s` is Show + the first Render of the dataset as Global Illumination: in the
background mode it returns with direct light while the links build; `solved_s` is when
its first solution was drawn; `apply_surface_s` is Show + first Render as Surface (in a
view of its own, before), for comparison. Prints the JSON and writes it to --output if given.
"""
import argparse
import json
import os
import platform
import statistics
import sys
import time

from paraview import servermanager
from paraview.simple import *  # noqa: F401,F403 (the pvbatch idiom)

parser = argparse.ArgumentParser()
parser.add_argument("--plugin", required=True)
parser.add_argument("--repeats", type=int, default=5)
parser.add_argument("--steps", type=int, default=10)
parser.add_argument("--output")
parser.add_argument("--datasets", default="wavelet40,wavelet64")
parser.add_argument("--count-solutions", action="store_true",
                    help="count the orbit frames that drew a new solution (an information "
                         "request between frames, outside the timing)")
arguments = parser.parse_args(sys.argv[1:])
LoadPlugin(arguments.plugin, remote=False, ns=globals())

EXTENTS = {"wavelet40": 40, "wavelet64": 64}


def cpu_name():
    try:
        with open("/proc/cpuinfo") as info:
            for line in info:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor()


def information(display, name):
    display.SMProxy.UpdatePropertyInformation()
    return display.SMProxy.GetProperty("GlobalIllumination" + name).GetElement(0)


def has_background_mode(display):
    return display.GetProperty("GlobalIlluminationWait") is not None


def thread_cpu_ms():
    """CPU time (user + system, ms) of this process's threads by group: "render" (the main
    thread, which renders and runs the filter), "llvmpipe" (Mesa's rasterizer threads),
    "linkgi-async" (the background solve: each update runs on a thread of its own, so this
    group also has the time of every thread that ended, which the process's total keeps), and
    "other". Linux only; empty elsewhere."""
    groups = {}
    tick_ms = 1000.0 / os.sysconf("SC_CLK_TCK")
    try:
        tids = os.listdir("/proc/self/task")
    except OSError:
        return groups
    for tid in tids:
        try:
            with open("/proc/self/task/%s/stat" % tid) as f:
                stat = f.read()
            with open("/proc/self/task/%s/comm" % tid) as f:
                comm = f.read().strip()
        except OSError:
            continue  # the thread ended
        fields = stat[stat.rfind(")") + 2:].split()  # fields[11], [12]: utime, stime
        group = "render" if tid == str(os.getpid()) else \
            "llvmpipe" if comm.startswith("llvmpipe") else \
            comm if comm == "linkgi-async" else "other"
        groups[group] = groups.get(group, 0.0) + (int(fields[11]) + int(fields[12])) * tick_ms
    with open("/proc/self/stat") as f:
        stat = f.read()
    fields = stat[stat.rfind(")") + 2:].split()
    ended = (int(fields[11]) + int(fields[12])) * tick_ms - sum(groups.values())
    groups["linkgi-async"] = groups.get("linkgi-async", 0.0) + max(0.0, ended)
    return groups


def orbit(view, steps, display=None):
    """Mean ms per frame of `steps` orbit steps of 5 degrees, the CPU ms per frame of each
    thread group (thread_cpu_ms) over the orbit, and, given the `display` of a background
    Global Illumination row, how many frames drew a solution newer than the frame before
    (read between the timed renders; else None)."""
    camera = GetActiveCamera()
    elapsed = 0.0
    new_solutions = 0 if display is not None else None
    shown = information(display, "ShownRequest") if display is not None else None
    before = thread_cpu_ms()
    for _ in range(steps):
        camera.Azimuth(5)
        start = time.perf_counter()
        Render(view)
        elapsed += time.perf_counter() - start
        if display is not None:
            now = information(display, "ShownRequest")
            new_solutions += 1 if now != shown else 0
            shown = now
    after = thread_cpu_ms()
    cpu = {g: (t - before.get(g, 0.0)) / steps for g, t in after.items()}
    return 1000.0 * elapsed / steps, cpu, new_solutions


def row(view, display, setup, wait=None):
    """Runs of one row: `setup` sets the display and view, `wait` the orbit's wait mode."""
    setup(display, view)
    background = display.Representation == "Global Illumination" and \
        has_background_mode(display)
    if background:
        display.GlobalIlluminationWait = "Always"
    Render(view)  # a finished solution to start from
    if background and wait:
        display.GlobalIlluminationWait = wait
    runs, cpus, solutions = [], [], []
    for _ in range(arguments.repeats):
        view.CameraPosition, view.CameraFocalPoint, view.CameraViewUp = HOME
        ms, cpu, drawn = orbit(
            view, arguments.steps, display if background and arguments.count_solutions else None)
        runs.append(ms)
        cpus.append(cpu)
        solutions.append(drawn)
    if background:
        display.GlobalIlluminationWait = "Always"
        Render(view)  # let the worker finish before the next row
    groups = sorted({g for cpu in cpus for g in cpu})
    result = {"median_ms": round(statistics.median(runs), 1), "min_ms": round(min(runs), 1),
              "max_ms": round(max(runs), 1), "runs_ms": [round(r, 1) for r in runs],
              "cpu_ms_per_frame": {g: round(statistics.median(cpu.get(g, 0.0) for cpu in cpus), 1)
                                   for g in groups}}
    if solutions[0] is not None:
        result["new_solutions_per_orbit"] = solutions
    return result


def gi(key, shadows, point_light=False):
    def setup(display, view):
        display.Representation = "Global Illumination"
        display.GlobalIlluminationKeyLight = 1 if key else 0
        display.GlobalIlluminationShadows = 1 if shadows else 0
        if point_light:
            view.UseLight = 0
            view.AdditionalLights = [LAMP]
        else:
            view.UseLight = 1
            view.AdditionalLights = []
    return setup


def surface(display, view):
    display.Representation = "Surface"
    view.UseLight = 1
    view.AdditionalLights = []


def opengl_renderer():
    probe = CreateView("RenderView")
    Render(probe)
    report = probe.GetRenderWindow().ReportCapabilities() or ""
    Delete(probe)
    for line in report.splitlines():
        if line.startswith("OpenGL renderer string:"):
            return line.split(":", 1)[1].strip()
    return "unknown"


result = {"benchmark": "paraview-plugin/examples/benchmark_orbit.py",
          "machine": {"cpu": cpu_name(), "cores": os.cpu_count(),
                      "opengl": opengl_renderer(), "load_average": os.getloadavg()},
          "protocol": {"view": [800, 600], "steps": arguments.steps, "degrees": 5,
                       "repeats": arguments.repeats, "figure": "mean ms/frame per run"},
          "datasets": {}}

for name in arguments.datasets.split(","):
    extent = EXTENTS[name]
    view = CreateView("RenderView")
    view.ViewSize = [800, 600]
    SetActiveView(view)
    wavelet = Wavelet(WholeExtent=[-extent, extent] * 3)
    contour = Contour(Input=wavelet, ContourBy=["POINTS", "RTData"], Isosurfaces=[160.0])
    contour.UpdatePipeline()
    points = contour.GetDataInformation().GetNumberOfPoints()
    LAMP = CreateLight()
    LAMP.Coords = "Scene"
    LAMP.Type = "Positional"
    LAMP.ConeAngle = 180
    LAMP.Position = [extent * 0.5, extent * 2.0, extent * 1.5]
    LAMP.Intensity = float(extent * extent * 2)

    # For comparison: Show + first Render as Surface, in a view of its own.
    other = CreateView("RenderView")
    other.ViewSize = [800, 600]
    start = time.perf_counter()
    shown = Show(contour, other)
    other.ResetCamera()
    Render(other)
    apply_surface_s = time.perf_counter() - start
    Delete(shown)
    Delete(other)
    SetActiveView(view)

    # Apply: Show + first Render as Global Illumination, the links built from nothing.
    start = time.perf_counter()
    display = Show(contour, view)
    display.Representation = "Global Illumination"
    background = has_background_mode(display)
    if background:
        display.GlobalIlluminationWait = "Never"
    view.ResetCamera()
    Render(view)
    apply_s = time.perf_counter() - start
    if background:
        display.GlobalIlluminationWait = "Always"
        Render(view)
    solved_s = time.perf_counter() - start
    HOME = (list(view.CameraPosition), list(view.CameraFocalPoint), list(view.CameraViewUp))

    rows = {}
    rows["Surface"] = row(view, display, surface)
    rows["GI, key light not bounced, no shadows"] = row(view, display, gi(False, False), "Never")
    rows["GI, key light not bounced, shadows"] = row(view, display, gi(False, True), "Never")
    rows["GI, key light bounced (default), shadows"] = row(view, display, gi(True, True), "Never")
    if background:
        rows["GI, key light bounced (default), shadows, every frame waits"] = \
            row(view, display, gi(True, True), "In Scripts")
    rows["GI, one static scene point light, shadows"] = \
        row(view, display, gi(False, True, point_light=True), "Never")
    result["datasets"][name] = {
        "points": points, "background_mode": background,
        "apply_surface_s": round(apply_surface_s, 2), "apply_s": round(apply_s, 2),
        "solved_s": round(solved_s, 2), "rows": rows}
    Delete(display)
    Delete(contour)
    Delete(wavelet)
    Delete(view)

result["machine"]["load_average_after"] = os.getloadavg()
text = json.dumps(result, indent=2)
print(text)
if arguments.output:
    with open(arguments.output, "w") as out:
        out.write(text + "\n")
sys.stdout.flush()
os._exit(0)  # skip pvbatch's teardown of live proxies
