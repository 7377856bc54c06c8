"""linkgi.pyvista, in PyVista on Debian's VTK:

1. illuminate() gives bit for bit what vtkGlobalIlluminationFilter gives with the same
   settings (the keywords reach the properties they name), for two methods;
2. bad input raises an error that names the problem: an unknown method, a value outside a
   property's range (VTK would clamp it), an unknown keyword, no lights, a point cloud, a
   MultiBlock for add_mesh (illuminate lights one as a scene: the blocks shadow each other);
3. add_mesh() keeps PyVista's colouring: a colour-mapped plane under one directional light,
   where nothing bounces or is blocked, shows the colours plain add_mesh shows (CIEDE2000
   <= 2 at every sampled pixel);
4. add_mesh() draws a sphere's shadow on the floor (plain PyVista draws none), and light
   bounces into it: darker than the lit floor, not black as without bounces;
5. the exporters take the Plotter.

Usage: TestPyVista.py [output directory for the images]
"""
import os
import sys

import numpy as np
import pyvista as pv

import linkgi
import linkgi.pyvista as lgi
import linkgi_colour_difference as colour
from vtkmodules.vtkRenderingCore import vtkCoordinate

SIZE = (400, 400)


def fail(message):
    sys.exit("FAILED: " + message)


def sphere_on_plane():
    return (pv.Sphere(center=(0, 0, 1), radius=0.5, theta_resolution=48, phi_resolution=24)
            + pv.Plane(i_size=4, j_size=4, i_resolution=40, j_resolution=40))


def sun():
    """A directional scene light shining along (1, 0, -2)."""
    return pv.Light(position=(-1, 0, 2), focal_point=(0, 0, 0), light_type="scene light",
                    intensity=1.0)


def arrays(poly):
    return {name: np.asarray(pv.wrap(poly).point_data[name])
            for name in ("DirectIrradiance", "IndirectIrradiance", "Radiance")}


def check_keywords():
    mesh = sphere_on_plane()
    lamp = pv.Light(position=(1, -1, 3), positional=True, cone_angle=180, intensity=10,
                    attenuation_values=(0, 0, 1))
    cases = [
        (dict(bounces=2, rays=64), lambda gi: (gi.SetNumberOfBounces(2), gi.SetRaysPerVertex(64))),
        (dict(method="photon_mapping", photons=20000, gather_rays=64, albedo=(0.5, 0.6, 0.7)),
         lambda gi: (gi.SetMethodToPhotonMapping(), gi.SetNumberOfPhotons(20000),
                     gi.SetFinalGatherRays(64), gi.SetAlbedo(0.5, 0.6, 0.7))),
        # properties named with an acronym (VPL...) in snake case
        (dict(method="instant_radiosity", vpls=256, vpl_clamp_distance=0.02, vpl_compensation_rays=16),
         lambda gi: (gi.SetMethodToInstantRadiosity(), gi.SetNumberOfVPLs(256),
                     gi.SetVPLClampDistance(0.02), gi.SetVPLCompensationRays(16))),
    ]
    for keywords, configure in cases:
        lit = lgi.illuminate(mesh, lamp, **keywords)
        gi = linkgi.vtkGlobalIlluminationFilter()
        configure(gi)
        gi.AddLight(lamp)
        gi.SetInputData(mesh)
        gi.Update()
        expected = arrays(gi.GetOutput())
        got = arrays(lit)
        for name in expected:
            if not np.array_equal(expected[name], got[name]):
                fail(f"illuminate({keywords}) differs from the filter in {name}")
        if np.max(got["IndirectIrradiance"]) <= 0:
            fail(f"illuminate({keywords}) bounced no light")
        print(f"ok: illuminate({keywords}) is the filter's result bit for bit "
              f"({lit.field_data['LinkGI.Method'][0]})")


def expect_error(kind, words, call):
    try:
        call()
    except kind as error:
        text = str(error)
        if not all(word in text for word in words):
            fail(f"the {kind.__name__} does not say {words}: {text}")
        print(f"ok: {kind.__name__}: {text[:110]}")
        return
    fail(f"no {kind.__name__} for {words}")


def check_errors():
    mesh = sphere_on_plane()
    light = sun()
    expect_error(ValueError, ["unknown method", "links"],
                 lambda: lgi.illuminate(mesh, light, method="radiosity"))
    expect_error(ValueError, ["rays=10", "perfect square"],
                 lambda: lgi.illuminate(mesh, light, rays=10))
    expect_error(ValueError, ["bounces=5000"], lambda: lgi.illuminate(mesh, light, bounces=5000))
    expect_error(TypeError, ["bouncs="], lambda: lgi.illuminate(mesh, light, bouncs=2))
    expect_error(ValueError, ["no lights"], lambda: lgi.illuminate(mesh, None))
    expect_error(ValueError, ["albedo"], lambda: lgi.illuminate(mesh, light, albedo=1.5))
    cloud = pv.PolyData(np.random.default_rng(1).random((50, 3)))
    expect_error(RuntimeError, ["point cloud"], lambda: lgi.illuminate(cloud, light))
    parts = pv.MultiBlock({"sphere": pv.Sphere(center=(0, 0, 1), radius=0.5),
                           "floor": pv.Plane(i_size=4, j_size=4)})
    p = pv.Plotter(off_screen=True)
    expect_error(TypeError, ["MultiBlock", "one"], lambda: lgi.add_mesh(p, parts))
    if p.renderer.actors:
        fail("a refused MultiBlock left an actor in the plotter")
    lit = lgi.illuminate(parts, light)  # a MultiBlock is one scene
    if not isinstance(lit, pv.MultiBlock) or lit.keys() != ["sphere", "floor"]:
        fail(f"illuminate(MultiBlock) gave {type(lit).__name__} {getattr(lit, 'keys', list)()}")
    shadowed = np.asarray(lit["floor"]["DirectIrradiance"])[:, 0] == 0
    if not shadowed.any():
        fail("the sphere casts no shadow on the floor when lit as one MultiBlock")
    print(f"ok: illuminate(MultiBlock) lights its blocks as one scene "
          f"({int(shadowed.sum())} floor points in the sphere's shadow)")


def plotter():
    p = pv.Plotter(off_screen=True, window_size=SIZE, lighting=None)
    p.add_light(sun())
    p.set_background("black")
    p.camera.parallel_projection = True
    p.camera_position = [(0, 0, 10), (0, 0, 0), (0, 1, 0)]
    p.camera.parallel_scale = 2.0
    return p


def pixel(p, image, point):
    """The colour at world `point` in a screenshot of `p`."""
    coordinate = vtkCoordinate()
    coordinate.SetCoordinateSystemToWorld()
    coordinate.SetValue(*point)
    x, y = coordinate.GetComputedDisplayValue(p.renderer)
    return image[image.shape[0] - 1 - y, x, :3].astype(float)


def render(global_illumination, mesh, output, name, **kwargs):
    p = plotter()
    if global_illumination:
        lgi.add_mesh(p, mesh, environment_color=(0, 0, 0), **kwargs)  # a black sky
    else:
        p.add_mesh(mesh, **kwargs)
    image = p.screenshot(os.path.join(output, name) if output else None, return_img=True)
    return p, image


def check_colours(output):
    plane = pv.Plane(i_size=4, j_size=4, i_resolution=40, j_resolution=40)
    plane["height"] = plane.points[:, 0] + 0.5 * plane.points[:, 1]
    style = dict(scalars="height", cmap="coolwarm", show_scalar_bar=False)
    p, plain = render(False, plane, output, "PyVista-colours-plain.png", **style)
    _, gi = render(True, plane, output, "PyVista-colours-gi.png", **style)
    worst = 0.0
    samples = [(x, y, 0) for x in np.linspace(-1.8, 1.8, 9) for y in np.linspace(-1.8, 1.8, 9)]
    for point in samples:
        a, b = pixel(p, plain, point), pixel(p, gi, point)
        if a.sum() == 0:
            fail(f"the plain plane is black at {point}")
        worst = max(worst, colour.pixel_difference(a, b))
    if worst > 2.0:
        fail(f"add_mesh changes the colour map's colours: CIEDE2000 up to {worst:.2f}")
    print(f"ok: add_mesh shows PyVista's colours (largest CIEDE2000 {worst:.2f} over "
          f"{len(samples)} pixels)")


def luminance(rgb):
    return float(np.dot(rgb, (0.2126, 0.7152, 0.0722)))


def check_shadow(output):
    mesh = sphere_on_plane()
    p, plain = render(False, mesh, output, "PyVista-shadow-plain.png", color="white")
    drawn, gi = render(True, mesh, output, "PyVista-shadow-gi.png", color="white")
    _, direct = render(True, mesh, None, None, color="white", bounces=0)
    # The sun along (1, 0, -2) throws the sphere's shadow to x in [-0.06, 1.06] on the floor;
    # seen from above, the sphere hides |x| <= 0.5 of it.
    shadow, lit = (0.85, 0.0, 0.0), (-1.5, 1.5, 0.0)

    def ratio(image):
        return luminance(pixel(p, image, shadow)) / luminance(pixel(p, image, lit))

    print(f"shadow / lit floor: plain PyVista {ratio(plain):.3f}, add_mesh {ratio(gi):.3f}, "
          f"add_mesh without bounces {ratio(direct):.3f}")
    if ratio(plain) < 0.95:
        fail("plain PyVista already darkens the shadow's place: the test does not test")
    if ratio(direct) > 0.01:
        fail("without bounces and under a black sky the shadow is not black")
    if not ratio(direct) + 0.01 < ratio(gi) < 0.5:
        fail(f"add_mesh's shadow is not a shadow with bounced light in it ({ratio(gi):.3f})")
    print("ok: add_mesh draws the shadow, and light bounces into it")
    return drawn


def check_export(p, output):
    """The exporters take a Plotter: its one global illumination actor, every vertex."""
    scene = linkgi.bake(p)
    points = sum(len(part.points) for part in scene.parts)
    if len(scene.parts) != 1 or points != sphere_on_plane().n_points:
        fail(f"bake(plotter) found {len(scene.parts)} parts of {points} points")
    if output:
        report = linkgi.export_glb(p, os.path.join(output, "PyVista.glb"))
        print(f"ok: export_glb(plotter): {report}")
    print(f"ok: bake(plotter): {points} vertices")


def main():
    output = sys.argv[1] if len(sys.argv) > 1 else None
    if output:
        os.makedirs(output, exist_ok=True)
    check_keywords()
    check_errors()
    check_colours(output)
    check_export(check_shadow(output), output)


if __name__ == "__main__":
    main()
