"""pvbatch test of volume shading in the "Hybrid Octree Volume" representation.

    pvbatch test_shade.py --plugin <HybridOctree.so> --cli <hybrid-octree> --workdir <dir>

The representation inherits Shade, Ambient, Diffuse, Specular and
SpecularPower from ParaView's volume representation (they set the
vtkVolumeProperty the mapper reads). A 64^3 Shepp-Logan phantom, Shade on
(ParaView's render view lights it with its light kit), in one view:
ParaView's "Volume" representation against "Hybrid Octree Volume" at the
default budget: RMSE at most 0.03, the plan "volume-shaded"; the shaded
picture differs from the unshaded one (RMSE above 0.01); with Ambient 1,
Diffuse 0 and Specular 0 under a headlight (the light kit off, one light of
Coords "Headlight" added) the plan is "volume" again. (With the light kit
switched off and no light added the renderer has no light, and VTK shades
every sample black: tests/paraview/test_property_matrix.py.)
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from paraview.simple import *  # noqa: E402,F401,F403
from effect_test import EffectTest, statistic  # noqa: E402
from pvtest import Checks, report, rmse  # noqa: E402
from representation_scene import look_at, make_view, show_volume  # noqa: E402

test = EffectTest()
t = Checks("HybridOctree shading test")
HYBRID = "Hybrid Octree Volume"
args, reader, array = test.args, test.reader, test.array
value_range, bounds = test.value_range, test.bounds


screenshot = test.screenshot


def plan(display):
    return statistic(display, "LastPlan")


view = make_view()
baseline_display = show_volume(reader, view, array, "Volume", value_range)
baseline_display.Shade = 1
look_at(view, bounds)
baseline = screenshot(view, "shaded-volume")
display = show_volume(reader, view, array, HYBRID, value_range)
display.Shade = 0
look_at(view, bounds)
unshaded = screenshot(view, "hybrid-unshaded")
display.Shade = 1
shaded = screenshot(view, "hybrid-shaded")
error = rmse(shaded, baseline)
change = rmse(shaded, unshaded)
report("shaded: RMSE %.4f against ParaView's shaded Volume, %.4f against unshaded" % (error, change))
t.check(plan(display) == "volume-shaded", "plan 'volume-shaded': %r" % plan(display))
t.check(error <= 0.03, "RMSE %.4f against ParaView's shaded Volume (threshold 0.03)" % error)
t.check(change > 0.01, "the shading shows: RMSE %.4f against unshaded" % change)
view.UseLight = 0  # the light kit off
headlight = AddLight(view=view)
headlight.Coords = "Headlight"
display.Ambient = 1.0
display.Diffuse = 0.0
display.Specular = 0.0
Render(view)
t.check(plan(display) == "volume", "identity shading is planned 'volume': %r" % plan(display))
t.finish()
