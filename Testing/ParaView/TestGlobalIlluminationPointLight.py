"""pvbatch: a Light Inspector point light lights the Global Illumination representation as it
lights Surface. The light (intensity 1, VTK's default attenuation: no falloff with distance)
sits 7 units in front of a plane of colour patches (ParaView's Cool to Warm at 9 points, the
primaries and secondaries, white, a dark grey), the view's light kit off. Nothing bounces
and nothing is shadowed, so every patch must be within CIEDE2000 2.0 of Surface's pixel, and
the image no darker than Surface's.
"""
import linkgi_paraview_testing as t
from paraview.simple import *  # noqa: F401,F403 (the pvbatch idiom)

import linkgi_colour_difference as colour
import linkgi_colour_patches as patches

DISTANCE = 7.0

arguments = t.parse_arguments()
t.load_plugin(arguments.plugin, globals())
colours = colour.cool_to_warm_and_primaries()
n = len(colours)
producer, view = patches.patch_view(colours)
view.UseLight = 0  # no light kit: the point light alone
light = CreateLight()
light.Coords, light.Type = "Scene", "Positional"
light.Position = [n / 2.0, 0.5, DISTANCE]
light.FocalPoint = [n / 2.0, 0.5, 0]
light.ConeAngle = 90  # 90 or more: a point light, no spot
light.Intensity = 1.0
view.AdditionalLights = [light]
surface, gi = patches.compare_with_surface(producer, view, colours, "PointLight", arguments.output_dir)
t.check(sum(map(sum, gi)) >= 0.98 * sum(map(sum, surface)),
        "Global Illumination is no darker than Surface (%d vs %d)"
        % (sum(map(sum, gi)), sum(map(sum, surface))))
t.check(min(sum(p) for p in surface) > 0, "every patch is lit by the point light")
