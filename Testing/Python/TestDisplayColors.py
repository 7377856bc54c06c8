"""vtkGlobalIlluminationDisplayColors bakes what the mapper displays: the baked colours,
drawn unlit by VTK at the same camera, match the global illumination mapper's picture
(mean CIEDE2000 over the covered pixels <= 2, the difference being the mapper's per-pixel
shadows and direct light against per-vertex ones) in a lamp scene (automatic exposure,
exponential curve) and a colour-mapped scene under a directional light (hue-preserving
display); and the light terms add up: direct and indirect differ from combined where there
is bounced light.

Usage: TestDisplayColors.py [output directory for the images]
"""
import os
import sys

import numpy as np

import linkgi
import linkgi_export_testing as testing


def check(name, window, out):
    scene = linkgi.bake(window)
    mapper_image = testing.grab(window)
    baked_image = testing.grab(testing.baked_window(scene, "combined"))
    testing.write_png(mapper_image, os.path.join(out, f"DisplayColors-{name}-mapper.png"))
    testing.write_png(baked_image, os.path.join(out, f"DisplayColors-{name}-baked.png"))
    background = tuple(int(round(255 * c)) for c in scene.background)
    difference, covered = testing.mean_difference(mapper_image, baked_image, background)
    print(f"{name}: mean CIEDE2000 {difference:.2f} over {covered} pixels")
    assert covered > 0.3 * mapper_image.shape[0] * mapper_image.shape[1], covered
    assert difference <= 2.0, f"{name}: baked colours differ from the mapper's: {difference:.2f}"
    part = scene.parts[0]
    combined = part.colors["combined"].astype(int)
    direct = part.colors["direct"].astype(int)
    indirect = part.colors["indirect"].astype(int)
    # Bounced light brightens: combined is never darker than direct, and brighter somewhere.
    assert (combined >= direct - 1).all(), f"{name}: combined darker than direct"
    assert (combined.sum(axis=1) > direct.sum(axis=1) + 3).any(), f"{name}: no bounced light"
    assert indirect.max() > 0 and (indirect.sum(axis=1) < combined.sum(axis=1)).any()
    return scene


out = testing.output_dir(sys.argv)
lamp = check("lamp", testing.lamp_scene(), out)
assert lamp.parts and lamp.mode == "combined"
check("colour-map", testing.colour_map_scene(), out)
print("ok")
