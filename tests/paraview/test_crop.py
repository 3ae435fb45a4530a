"""pvbatch test of volume cropping in the "Hybrid Octree Volume" representation.

    pvbatch test_crop.py --plugin <HybridOctree.so> --cli <hybrid-octree> --workdir <dir>

The representation inherits UseCropping, CroppingOrigin and CroppingScale
from ParaView's volume representation (vtkImageVolumeRepresentation turns
them into the mapper's cropping region planes, origin + bounds * scale per
axis, VTK's default subvolume flags). A 64^3 Shepp-Logan phantom in one
view: ParaView's "Volume" representation against "Hybrid Octree Volume",
both cropped to the same box: RMSE at most 0.03, the effects "cropping";
the cropped picture differs from the uncropped one (RMSE above 0.01);
ParaView's default box (origin 0, scale 1: the data bounds) removes
nothing: no effect, the uncropped picture (RMSE below 0.002).
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from paraview.simple import *  # noqa: E402,F401,F403
from effect_test import EffectTest, statistic  # noqa: E402
from pvtest import Checks, report, rmse  # noqa: E402
from representation_scene import look_at, make_view, show_volume  # noqa: E402

test = EffectTest()
t = Checks("HybridOctree cropping test")
HYBRID = "Hybrid Octree Volume"
args, reader, array = test.args, test.reader, test.array
value_range, bounds = test.value_range, test.bounds
# The box [o + bounds_min s, o + bounds_max s] per axis: about the middle
# 60 to 75 % of each axis, off centre.
extent = [bounds[2 * a + 1] - bounds[2 * a] for a in range(3)]
scale = [0.6, 0.75, 0.7]
origin = [bounds[2 * a] * (1.0 - scale[a]) + f * extent[a] for a, f in enumerate([0.1, 0.05, 0.25])]


screenshot = test.screenshot


def effects(display):
    return statistic(display, "LastEffects")


def crop(display, on):
    display.UseCropping = 1 if on else 0
    display.CroppingOrigin = origin if on else [0.0, 0.0, 0.0]
    display.CroppingScale = scale if on else [1.0, 1.0, 1.0]


view = make_view()
baseline_display = show_volume(reader, view, array, "Volume", value_range)
crop(baseline_display, True)
look_at(view, bounds)
baseline = screenshot(view, "cropped-volume")
display = show_volume(reader, view, array, HYBRID, value_range)
crop(display, False)
look_at(view, bounds)
uncropped = screenshot(view, "hybrid-uncropped")
t.check(effects(display) == "", "no cropping: no effect: %r" % effects(display))
crop(display, True)
cropped = screenshot(view, "hybrid-cropped")
error = rmse(cropped, baseline)
change = rmse(cropped, uncropped)
report("cropped: RMSE %.4f against ParaView's cropped Volume, %.4f against uncropped" % (error, change))
t.check(effects(display) == "cropping", "effects 'cropping': %r" % effects(display))
t.check(error <= 0.03, "RMSE %.4f against ParaView's cropped Volume (threshold 0.03)" % error)
t.check(change > 0.01, "the cropping shows: RMSE %.4f against uncropped" % change)
# Use Cropping with ParaView's default box, the data bounds: nothing removed.
display.UseCropping = 1
display.CroppingOrigin = [0.0, 0.0, 0.0]
display.CroppingScale = [1.0, 1.0, 1.0]
whole = screenshot(view, "hybrid-whole-box")
t.check(effects(display) == "", "the data bounds remove nothing: no effect: %r" % effects(display))
t.check(rmse(whole, uncropped) < 0.002, "the data bounds: the uncropped picture (RMSE %.4f)" % rmse(whole, uncropped))
t.finish()
