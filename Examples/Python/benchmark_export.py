"""Sizes and times of linkgi.export_html and linkgi.export_glb for large meshes.

    PYTHONPATH=build/lib/python3.11/dist-packages /usr/bin/python3 \\
        Examples/Python/benchmark_export.py [triangles ...] [--repeat N] [--out DIR]

A sphere of about the given number of triangles (default 100 000 and 1 000 000) carrying
light arrays as the filter writes them (the exporters' cost does not depend on how the
light was computed, so the arrays are analytic: a directional light and a constant bounce).
Prints one JSON record per mesh: medians over the repeats of the export time (baking plus
writing) for each format, the file sizes, and the time headless Chromium takes to open the
page and draw it (its wall time, minus that of an empty page).
"""
import argparse
import json
import os
import platform
import statistics
import subprocess
import tempfile
import time

import numpy as np

import linkgi
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.vtkRenderingCore import vtkCamera


def lit_sphere(triangles):
    # A UV sphere of resolution (t, p) has about 2 t (p - 2) triangles; take p = t / 2.
    theta = max(8, int(round(np.sqrt(triangles))))
    sphere = vtkSphereSource()
    sphere.SetThetaResolution(theta)
    sphere.SetPhiResolution(max(4, theta // 2 + 2))
    sphere.Update()
    surface = sphere.GetOutput()
    normals = vtk_to_numpy(surface.GetPointData().GetNormals())
    facing = np.clip(normals @ np.array([0.3, 0.4, 0.866]), 0, None)
    direct = np.repeat(facing[:, None], 3, axis=1).astype(np.float32)
    indirect = np.full_like(direct, 0.1)
    for name, values in (("DirectIrradiance", direct), ("IndirectIrradiance", indirect),
                         ("Radiance", (0.8 / np.pi) * (direct + indirect))):
        array = numpy_to_vtk(values, deep=True)
        array.SetName(name)
        surface.GetPointData().AddArray(array)
    return surface


def chromium_seconds(page, size=(800, 600)):
    with tempfile.TemporaryDirectory() as profile:
        start = time.perf_counter()
        subprocess.run(["chromium", "--headless=new", "--no-sandbox", "--disable-gpu",
                        "--use-gl=swiftshader", "--enable-unsafe-swiftshader",
                        f"--window-size={size[0]},{size[1]}", f"--user-data-dir={profile}",
                        "--virtual-time-budget=60000", f"--screenshot={profile}/shot.png",
                        f"file://{os.path.abspath(page)}"],
                       check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                       timeout=600)
        return time.perf_counter() - start


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("triangles", nargs="*", type=int, default=[100000, 1000000])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--out", default=tempfile.gettempdir())
    args = parser.parse_args()
    camera = vtkCamera()
    camera.SetPosition(0, -3, 1)
    camera.SetFocalPoint(0, 0, 0)
    camera.SetViewUp(0, 0, 1)
    empty = os.path.join(args.out, "linkgi-empty.html")
    with open(empty, "w") as f:
        f.write("<html><body></body></html>")
    for triangles in args.triangles:
        surface = lit_sphere(triangles)
        record = {"triangles": surface.GetNumberOfPolys(), "points": surface.GetNumberOfPoints(),
                  "machine": platform.node(), "cpus": os.cpu_count()}
        for kind, export in (("html", linkgi.export_html), ("glb", linkgi.export_glb)):
            path = os.path.join(args.out, f"linkgi-{triangles}.{kind}")
            seconds = []
            for _ in range(args.repeat):
                start = time.perf_counter()
                report = export(surface, path, camera=camera)
                seconds.append(time.perf_counter() - start)
            record[f"{kind}_bytes"] = report["bytes"]
            record[f"{kind}_export_s"] = statistics.median(seconds)
        blank = statistics.median(chromium_seconds(empty) for _ in range(args.repeat))
        opened = [chromium_seconds(os.path.join(args.out, f"linkgi-{triangles}.html"))
                  for _ in range(args.repeat)]
        record["html_open_s"] = statistics.median(opened) - blank
        record["html_open_s_range"] = [min(opened) - blank, max(opened) - blank]
        print(json.dumps(record), flush=True)


if __name__ == "__main__":
    main()
