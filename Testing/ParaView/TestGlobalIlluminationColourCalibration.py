"""pvbatch: the Global Illumination representation shows a colour map's colours as the
Surface representation does where light is only direct and unblocked: a plane facing the
camera in an open scene (black sky), default view lights (the light kit: key, fill, two
back and head lights), coloured through a colour map holding ParaView's default Cool to
Warm at 9 points, the primaries and secondaries, white and a dark grey. Every colour must
be within CIEDE2000 2.0 of Surface's pixel.
"""
import linkgi_paraview_testing as t
from paraview.simple import *  # noqa: F401,F403 (the pvbatch idiom)

import linkgi_colour_difference as colour
import linkgi_colour_patches as patches

arguments = t.parse_arguments()
t.load_plugin(arguments.plugin, globals())
colours = colour.cool_to_warm_and_primaries()
producer, view = patches.patch_view(colours)
t.check(view.UseLight == 1 and len(view.AdditionalLights) == 0, "the view has its default lights")
surface, gi = patches.compare_with_surface(producer, view, colours, "ColourCalibration", arguments.output_dir)
t.check(len(set(surface)) == len(colours) and min(sum(p) for p in surface) > 0,
        "every patch shows its own colour, lit by the light kit")
