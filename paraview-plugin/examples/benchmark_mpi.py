"""Benchmark of the Global Illumination representation under MPI: time and
per-rank peak memory for 1, 2 and 4 ranks, and what the ranks exchange.

Driver (any Python 3; runs pvbatch under mpirun and, if there is no display, Xvfb):

    python3 paraview-plugin/examples/benchmark_mpi.py --plugin <LinkGI.so> \
        [--ranks 1,2,4] [--repeats 5] [--extent 40] [--method 0] [--output result.json]

with PYTHONPATH holding ParaView's Python modules (as Testing/ParaView/CMakeLists.txt sets
it). Each run is `mpirun -np N --oversubscribe /usr/bin/time -f ... pvbatch --mpi
benchmark_mpi.py --child ...`: ParaView's Wavelet -extent..extent contoured at RTData 160
(54k points at extent 40), split by ParaView into one piece per rank as any parallel source
is, shown as Global Illumination under one scene point light (the light kit off), 64 rays,
3 bounces, view 400x400. A run measures, on rank 0 (every Render is collective, so these are
the slowest rank's):

- `first_s`: Show and the first Render (links, light links, bounces, the other ranks'
  triangles gathered for the shadow maps, shadow maps); renders wait for the solution;
- `light_move_s`: a Render after the light moved (light links, bounces, shadow maps);
- `frame_s`: the mean of 5 Renders after camera moves (nothing recomputed);

and `/usr/bin/time` gives every rank's peak resident memory (`maxrss_mb`, one per rank).
The triangles rank 0 received for its shadow maps (36 bytes each, once per geometry
change) and the bytes of the others' partitions its filter received at the first render
come from the representation. `--representation Surface` runs the same without
LinkGI: pvbatch's own memory per rank, to subtract. `--method` picks the representation's
Method (0 links, 1 instant radiosity, 2 implicit visibility, 3 photon mapping). The table gives medians, minimum and maximum over
`--repeats` runs and the ratios to one rank. On a machine with fewer cores than ranks the
ranks share cores: the ratios then show the overhead of the partitioning, not a speed-up.
"""
import argparse
import json
import os
import platform
import re
import shutil
import statistics
import subprocess
import sys
import time

HERE = os.path.abspath(__file__)


def child(arguments):
    """One run, inside pvbatch --mpi (the script runs on rank 0)."""
    from paraview import servermanager
    from paraview import simple

    simple.LoadPlugin(arguments.plugin, remote=False, ns=globals())
    ranks = servermanager.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()
    e = arguments.extent
    wavelet = simple.Wavelet(WholeExtent=[-e, e, -e, e, -e, e])
    contour = simple.Contour(Input=wavelet, ContourBy=["POINTS", "RTData"], Isosurfaces=[160.0])
    contour.UpdatePipeline()
    info = contour.GetDataInformation()

    view = simple.CreateView("RenderView")
    view.ViewSize = [400, 400]
    view.OrientationAxesVisibility = 0
    view.UseLight = 0
    light = simple.CreateLight()
    light.Coords = "Scene"
    light.Type = "Positional"
    light.ConeAngle = 180
    light.Position = [0.0, 0.0, 3.0 * e]
    light.Intensity = 4.0 * e * e
    view.AdditionalLights = [light]

    started = time.perf_counter()
    display = simple.Show(contour, view)
    display.Representation = arguments.representation
    if arguments.representation == "Global Illumination":
        display.GlobalIlluminationRays = arguments.rays
        display.GlobalIlluminationBounces = arguments.bounces
        display.GlobalIlluminationMethod = arguments.method
    simple.ResetCamera(view)
    simple.Render(view)
    first = time.perf_counter() - started
    proxy = display.SMProxy
    proxy.UpdatePropertyInformation()
    partition_bytes = (proxy.GetProperty("GlobalIlluminationPartitionBytes").GetElement(0)
                       if arguments.representation == "Global Illumination"
                       and proxy.GetProperty("GlobalIlluminationPartitionBytes") else None)

    light.Position = [0.5 * e, 0.0, 3.0 * e]
    started = time.perf_counter()
    simple.Render(view)
    light_move = time.perf_counter() - started

    frames = []
    for _ in range(5):
        view.GetActiveCamera().Azimuth(5)
        started = time.perf_counter()
        simple.Render(view)
        frames.append(time.perf_counter() - started)

    proxy.UpdatePropertyInformation()

    def counter(name):
        if arguments.representation != "Global Illumination":
            return 0
        prop = proxy.GetProperty("GlobalIllumination" + name)
        return prop.GetElement(0) if prop is not None else None  # older plugins lack some

    result = {
        "ranks": ranks,
        "points": info.GetNumberOfPoints(),
        "triangles": info.GetNumberOfCells(),
        "first_s": first,
        "light_move_s": light_move,
        "frame_s": statistics.mean(frames),
        "rank0_remote_triangles": counter("GlobalCasterTriangles"),
        "caster_gathers": counter("GlobalCasterGathers"),
        "link_builds": counter("LinkBuilds"),
        "light_link_builds": counter("LightLinkBuilds"),
        "bounce_runs": counter("BounceRuns"),
        # The filter's exchange of the partitions (rank 0 received), once per geometry change.
        "rank0_partition_bytes": partition_bytes,
    }
    print("LINKGI_RESULT " + json.dumps(result))
    sys.stdout.flush()


def run_once(arguments, ranks, attempts=3):
    """One run; retried when a rank's peak-memory line went missing (mpirun may end the
    other ranks before /usr/bin/time prints)."""
    for attempt in range(attempts):
        result = try_once(arguments, ranks)
        if result is not None:
            return result
        print("ranks %d: a peak memory line is missing, run again" % ranks, file=sys.stderr)
    sys.exit("ranks %d: peak memory lines missing in %d attempts" % (ranks, attempts))


def try_once(arguments, ranks):
    mpirun = shutil.which("mpirun")
    command = [mpirun, "-np", str(ranks), "--oversubscribe",
               "/usr/bin/time", "-f", "LINKGI_MAXRSS_KB %M",
               arguments.pvbatch, "--mpi", HERE, "--child", "--plugin", arguments.plugin,
               "--extent", str(arguments.extent), "--rays", str(arguments.rays),
               "--bounces", str(arguments.bounces), "--method", str(arguments.method),
               "--representation", arguments.representation]
    if not os.environ.get("DISPLAY") and arguments.xvfb:
        command = [arguments.xvfb] + command
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    started = time.perf_counter()
    done = subprocess.run(command, env=env, capture_output=True, text=True, timeout=1200)
    wall = time.perf_counter() - started
    output = done.stdout + done.stderr
    found = re.search(r"LINKGI_RESULT (\{.*\})", output)
    if done.returncode != 0 or not found:
        sys.exit("run on %d ranks failed (%d):\n%s" % (ranks, done.returncode, output[-4000:]))
    result = json.loads(found.group(1))
    rss = [int(kb) / 1024.0 for kb in re.findall(r"LINKGI_MAXRSS_KB (\d+)", output)]
    if len(rss) != ranks:
        return None
    result["maxrss_mb"] = sorted(rss)
    result["wall_s"] = wall
    result["loadavg_1min_after"] = os.getloadavg()[0]  # other work on the machine
    return result


def summary(values):
    return {"median": statistics.median(values), "min": min(values), "max": max(values)}


def driver(arguments):
    runs = {}
    for ranks in [int(r) for r in arguments.ranks.split(",")]:
        runs[ranks] = []
        for repeat in range(arguments.repeats):
            result = run_once(arguments, ranks)
            print("ranks %d run %d: %s" % (ranks, repeat, json.dumps(result)), file=sys.stderr)
            runs[ranks].append(result)
    table = {}
    base = None
    for ranks, results in runs.items():
        row = {key: summary([r[key] for r in results])
               for key in ("first_s", "light_move_s", "frame_s")}
        row["max_rank_maxrss_mb"] = summary([max(r["maxrss_mb"]) for r in results])
        row["sum_maxrss_mb"] = summary([sum(r["maxrss_mb"]) for r in results])
        last = results[-1]
        for key in ("points", "triangles", "rank0_remote_triangles", "caster_gathers",
                    "link_builds", "light_link_builds", "bounce_runs", "rank0_partition_bytes"):
            row[key] = last[key]
        # What rank 0 receives: the others' triangles once per geometry change (36 B each),
        # and, once the filter exchanges radiance between ranks, 16 B per element of the
        # others per bounce (about their share of the points).
        row["rank0_caster_bytes"] = 36 * last["rank0_remote_triangles"]
        row["rank0_radiance_bytes_per_bounce_model"] = int(
            16 * last["points"] * (ranks - 1) / ranks)
        if base is None:
            base = row
        row["ratio_to_1_rank"] = {
            "first_s": row["first_s"]["median"] / base["first_s"]["median"],
            "light_move_s": row["light_move_s"]["median"] / base["light_move_s"]["median"],
            "frame_s": row["frame_s"]["median"] / base["frame_s"]["median"],
            "max_rank_maxrss_mb": row["max_rank_maxrss_mb"]["median"] /
            base["max_rank_maxrss_mb"]["median"],
        }
        table[str(ranks)] = row
    out = {
        "benchmark": "benchmark_mpi.py",
        "machine": {"cpu": cpu_name(), "cores": os.cpu_count(), "host": platform.node()},
        "settings": {"representation": arguments.representation, "method": arguments.method,
                     "extent": arguments.extent, "rays": arguments.rays,
                     "bounces": arguments.bounces, "repeats": arguments.repeats},
        "results": table,
        "runs": {str(k): v for k, v in runs.items()},
    }
    text = json.dumps(out, indent=1)
    print(text)
    if arguments.output:
        with open(arguments.output, "w") as f:
            f.write(text + "\n")


def cpu_name():
    try:
        with open("/proc/cpuinfo") as info:
            for line in info:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor()


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--plugin", required=True)
    parser.add_argument("--child", action="store_true", help="(internal) one run in pvbatch")
    parser.add_argument("--ranks", default="1,2,4")
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--extent", type=int, default=40)
    parser.add_argument("--rays", type=int, default=64)
    parser.add_argument("--bounces", type=int, default=3)
    parser.add_argument("--method", type=int, default=0,
                        help="0 links, 1 instant radiosity, 2 implicit visibility, 3 photon mapping")
    parser.add_argument("--representation", default="Global Illumination",
                        help="Surface: the same runs without LinkGI, for pvbatch's own memory")
    parser.add_argument("--pvbatch", default=shutil.which("pvbatch") or "pvbatch")
    parser.add_argument("--xvfb", default=os.path.join(
        os.path.dirname(HERE), "..", "..", "Testing", "run_with_xvfb.sh"))
    parser.add_argument("--output")
    arguments = parser.parse_args(sys.argv[1:])
    if arguments.child:
        child(arguments)
    else:
        driver(arguments)


main()
