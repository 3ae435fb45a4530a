"""pvbatch test of the "View Selection" of the "Hybrid Octree Volume"
representation (with "Smallest Texel (pixels)" and "View Change (degrees)").

    pvbatch test_view_selection.py --plugin <HybridOctree.so> --cli <hybrid-octree> --workdir <dir>

A 64^3 Shepp-Logan phantom (f32, 1.05 MB at full resolution) in one view,
ParaView's "Volume" as the reference. "Hybrid Octree Volume" with a
texture budget of 0.5 MB (under half the volume: the selection chooses) and View Selection set to each value, Data, Screen Space,
Visibility and Both: each draws within RMSE 0.03 of *Volume* (the bound of
test_shade.py on this scene) and the representation reports the view
importance that ran ("data", "screen", "visibility", "both"). Under Both,
turning the camera 2 degrees keeps the selection (View Change 5 degrees),
8 degrees selects again; View Change 0 selects again at a 1 degree turn.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from paraview.simple import GetActiveCamera, Hide, Render  # noqa: E402,F401
from effect_test import EffectTest, statistic  # noqa: E402
from pvtest import Checks, report, rmse  # noqa: E402
from representation_scene import look_at, make_view, show_volume  # noqa: E402

test = EffectTest()
t = Checks("HybridOctree view selection test")
HYBRID = "Hybrid Octree Volume"
BOUND = 0.03
MODES = [("Data", "data"), ("Screen Space", "screen"), ("Visibility", "visibility"), ("Both", "both")]

view = make_view()
baseline_display = show_volume(test.reader, view, test.array, "Volume", test.value_range)
look_at(view, test.bounds)
baseline = test.screenshot(view, "volume")
Hide(test.reader, view)
display = show_volume(test.reader, view, test.array, HYBRID, test.value_range)
display.TextureBudgetMB = 0.5
look_at(view, test.bounds)
for text, name in MODES:
    display.ViewSelection = text
    picture = test.screenshot(view, "hybrid-" + name)
    error = rmse(picture, baseline)
    ran = statistic(display, "LastViewSelection")
    report("%-12s ran %-10s texture MB %.3f, RMSE %.4f against ParaView's Volume (bound %.2f)"
           % (text, ran, statistic(display, "LastTextureMB"), error, BOUND))
    t.check(ran == name, "%s: the view selection that ran is %r, not %r" % (text, name, ran))
    t.check(error <= BOUND, "%s: RMSE %.4f against ParaView's Volume (bound %.2f)" % (text, error, BOUND))

# Under Both the selection follows the view past View Change degrees only.
display.ViewSelection = "Both"
Render(view)
camera = GetActiveCamera()


def turn(degrees):
    camera.Azimuth(degrees)
    Render(view)
    return statistic(display, "LastReselected")


t.check(turn(2.0) == 0, "a 2 degree turn keeps the selection")
t.check(turn(8.0) == 1, "an 8 degree turn selects again")
display.ViewChangeDegrees = 0.0
Render(view)
t.check(turn(1.0) == 1, "View Change 0: a 1 degree turn selects again")
t.finish()
