"""Client and server: the Global Illumination representation rendered by
`mpiexec -np 2 pvserver` and composited by IceT, as a ParaView GUI connected to a cluster
sees it; with --ranks 1, the background solve of a one-process server (a parallel server
solves synchronously), whose state the GUI's watcher polls from the client; with --gui
<paraview>, that GUI itself runs TestGlobalIlluminationGUIRemote.py against the server.

Run with Python and ParaView's modules (as the pvbatch tests' PYTHONPATH). This process
starts `<mpiexec> -np <ranks> [flags] pvserver` on a free port and runs itself again as the
client (--port), which connects, loads the plugin on both sides, keeps the rendering on
the server (Remote Render Threshold 0) and runs the checks of linkgi_mpi_scene.py against
the same baseline as the pvbatch runs. The server exits when its client does.
Arguments: --plugin, --baseline-dir, --output-dir as the pvbatch tests, and --mpiexec
<path> [--mpiexec-flag <flag>]... --pvserver <path> [--ranks <n>, default 2] [--gui <path>].
"""
import argparse
import os
import socket
import subprocess
import sys
import time

parser = argparse.ArgumentParser()
parser.add_argument("--plugin", required=True)
parser.add_argument("--baseline-dir", required=True)
parser.add_argument("--output-dir", required=True)
parser.add_argument("--mpiexec")
parser.add_argument("--mpiexec-flag", action="append", default=[])
parser.add_argument("--pvserver")
parser.add_argument("--ranks", type=int, default=2)
parser.add_argument("--gui", help="the paraview executable: the GUI is the client")
parser.add_argument("--port", type=int, help="(internal) be the client of this port")
arguments = parser.parse_args(sys.argv[1:])


def client():
    from paraview import servermanager
    from paraview import simple

    import linkgi_mpi_scene
    import linkgi_paraview_testing as t

    simple.Connect("localhost", arguments.port)
    ranks = servermanager.ActiveConnection.GetNumberOfDataPartitions()
    t.check(ranks == arguments.ranks, "the server has %d ranks (has %d)" % (arguments.ranks, ranks))
    if not os.path.exists(arguments.plugin):
        t.fail("the plugin %s was not built" % arguments.plugin)
    simple.LoadPlugin(arguments.plugin, remote=True, ns=globals())
    simple.LoadPlugin(arguments.plugin, remote=False, ns=globals())
    # Render on the ranks (IceT), never on the client with the delivered geometry.
    simple.GetSettingsProxy("RenderViewSettings").RemoteRenderThreshold = 0
    if ranks == 1:
        check_state_from_server(simple, t)
    else:
        linkgi_mpi_scene.run(arguments, ranks, counters_here=False)


def check_state_from_server(simple, t):
    """What the GUI's watcher polls, GlobalIlluminationState, is the server's: ParaView pulls
    information properties from the client's own copy of the representation, which has no
    data while the server renders, so without the gathering it read IDLE and a new solution
    was never drawn by itself."""
    view = simple.CreateView("RenderView")
    view.ViewSize = [160, 160]
    # 40k points: the links take the server's worker a second or more, longer than the
    # renders that one Render() may make there (the second would draw a quicker solution).
    display = simple.Show(simple.Sphere(ThetaResolution=200, PhiResolution=200), view)
    display.Representation = "Global Illumination"
    display.GlobalIlluminationWait = 0  # Never: the GUI's renders
    display.GlobalIlluminationRays = 64
    proxy = display.SMProxy

    def state():
        proxy.UpdatePropertyInformation()
        return proxy.GetProperty("GlobalIlluminationState").GetElement(0)

    simple.Render(view)  # hands the scene to the server's worker and draws direct light
    first = state()
    t.check(first in (1, 2), "after the first render the server solves or has solved "
            "(state %d; 1 = solving, 2 = ready)" % first)
    deadline = time.time() + 120
    now = first
    while now != 2 and time.time() < deadline:
        time.sleep(0.1)
        now = state()
    t.check(now == 2, "the server's solution is reported ready (state %d)" % now)
    # A render that moved the camera-following key light (the first renders may) asks for
    # one more solution: render whenever one is ready, until nothing is pending.
    simple.Render(view)
    after = state()
    while after != 0 and time.time() < deadline:
        time.sleep(0.1)
        after = state()
        if after == 2:
            simple.Render(view)
            after = state()
    t.check(after == 0, "once drawn, nothing is pending (state %d)" % after)
    simple.Delete(display)
    simple.Delete(view)


def free_port():
    with socket.socket() as s:
        s.bind(("localhost", 0))
        return s.getsockname()[1]


def manager():
    port = free_port()
    # The Python client loads the plugin on both sides itself; the GUI's script cannot
    # before the connection exists, so both load it by name at startup.
    server_plugin = ["--plugin-search-paths=" + os.path.dirname(os.path.abspath(arguments.plugin)),
                     "--plugins=LinkGI"] if arguments.gui else []
    os.makedirs(arguments.output_dir, exist_ok=True)
    log_path = os.path.join(arguments.output_dir, "pvserver.log")

    def server_log():
        with open(log_path) as f:
            return f.read()

    with open(log_path, "w") as log:
        server = subprocess.Popen(
            [arguments.mpiexec, "-np", str(arguments.ranks)] + arguments.mpiexec_flag +
            [arguments.pvserver, "--server-port=%d" % port] + server_plugin,
            stdout=log, stderr=subprocess.STDOUT)
    code = 1
    try:
        deadline = time.time() + 120
        while "Accepting connection" not in server_log():
            if server.poll() is not None or time.time() > deadline:
                print("FAILED: pvserver did not start:\n" + server_log())
                return 1
            time.sleep(0.2)
        if arguments.gui:
            code = subprocess.call([arguments.gui, "--dr", "--url=cs://localhost:%d" % port] +
                                   server_plugin + ["--script=" + os.path.join(
                                       os.path.dirname(os.path.abspath(__file__)),
                                       "TestGlobalIlluminationGUIRemote.py")])
        else:
            code = subprocess.call([sys.executable, os.path.abspath(__file__),
                                    "--port", str(port), "--ranks", str(arguments.ranks),
                                    "--plugin", arguments.plugin,
                                    "--baseline-dir", arguments.baseline_dir,
                                    "--output-dir", arguments.output_dir])
        server.wait(60)  # it exits with its client
    except subprocess.TimeoutExpired:
        print("FAILED: pvserver did not exit after its client")
        code = 1
    finally:
        if server.poll() is None:
            server.kill()
            server.wait()
        log = server_log()
        if arguments.gui:
            # The GUI's script can only end its process (os._exit), which the server reports
            # as two socket errors: those are expected, any other error is not.
            log = "\n".join(line.replace("ERR|", "(the GUI exited)")
                             if "Could not receive tag" in line or
                             "Some error in socket processing" in line else line
                             for line in log.splitlines())
        print(log)  # the server's warnings
    return code


if arguments.port:
    client()
else:
    sys.exit(manager())
