"""LinkGI in PyVista: the hex nut that ships with PyVista, standing on a floor under a lamp
(1/r^2),
drawn by PyVista alone and with LinkGI's shadows and bounced light.

  PYTHONPATH=build/lib/python3.11/dist-packages xvfb-run -a build/venv/bin/python \\
    Examples/Python/pyvista_nut.py pyvista_nut.png

build/venv is Debian's Python with PyVista 0.46.5 (scripts/setup.sh makes it).
"""
import sys

import pyvista as pv
from pyvista import examples

import linkgi.pyvista as lgi

nut = examples.load_nut()
nut.translate((-nut.center[0], -nut.center[1], -nut.bounds[4]), inplace=True)
size = 3 * max(nut.bounds[1] - nut.bounds[0], nut.bounds[3] - nut.bounds[2])
floor = pv.Plane(i_size=size, j_size=size, i_resolution=80, j_resolution=80)
scene = nut + floor  # one mesh: the nut shadows the floor, and light bounces between them

plotter = pv.Plotter(shape=(1, 2), off_screen=True, window_size=(1200, 500), lighting="none")
lamp = (0.3 * size, -0.25 * size, 0.6 * size)
reach = sum(c * c for c in lamp)  # the lamp's distance squared: irradiance 1 at the nut
for column, title in enumerate(("PyVista", "LinkGI: shadows and bounced light")):
    plotter.subplot(0, column)
    plotter.add_text(title, font_size=12)
    plotter.set_background("#2b2f3a")
    plotter.add_light(pv.Light(position=lamp, positional=True, cone_angle=180,
                               intensity=reach, attenuation_values=(0, 0, 1)))  # 1/r^2
    if column == 0:
        plotter.add_mesh(scene, color="tan", smooth_shading=True)
    else:
        lgi.add_mesh(plotter, scene, color="tan", smooth_shading=True, bounces=3)
    plotter.camera_position = [(0.9 * size, -1.2 * size, 0.8 * size), (0, 0, 0.1 * size),
                               (0, 0, 1)]
plotter.screenshot(sys.argv[1] if len(sys.argv) > 1 else "pyvista_nut.png")
