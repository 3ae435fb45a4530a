"""pvbatch test of "Target Frame (ms)" of the "Hybrid Octree Volume"
representation and the statistics that show its price.

    pvbatch test_time_target.py --plugin <HybridOctree.so> --cli <hybrid-octree> --workdir <dir>

A 64^3 Shepp-Logan phantom at a texture budget of 0.5 MB, ParaView's
"Volume" as the reference. Untimed, the representation reports no target and
no outcome, and an Estimated RMS Error above 0 (the budget is below the full
resolution). With a target of 100 s the first frames warm the cost model up
("warm-up"), then every frame is "full": the untimed frame's Estimated RMS
Error and a picture within RMSE 0.03 of *Volume* (test_view_selection.py's
bound). With a target of 1 microsecond the frames after the warm-up are
"below-fastest", fewer texture MB and a larger Estimated RMS Error. A
target of -5 draws nothing (the mapper's error); 0 draws again.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from paraview.simple import Hide, Render  # noqa: E402
from effect_test import EffectTest, statistic  # noqa: E402
from pvtest import Checks, report, rmse  # noqa: E402
from representation_scene import look_at, make_view, show_volume  # noqa: E402

test = EffectTest()
t = Checks("HybridOctree time target test")
BOUND = 0.03
WARM_UP = 4

view = make_view()
show_volume(test.reader, view, test.array, "Volume", test.value_range)
look_at(view, test.bounds)
baseline = test.screenshot(view, "volume")
Hide(test.reader, view)
display = show_volume(test.reader, view, test.array, "Hybrid Octree Volume", test.value_range)
display.TextureBudgetMB = 0.5
look_at(view, test.bounds)


def frame():
    Render(view)
    s = {name: statistic(display, name) for name in
         ("LastTargetMilliseconds", "LastDrawTargetMilliseconds", "LastPredictedMilliseconds",
          "LastDrawMilliseconds",
          "LastTimeOutcome", "LastEstimatedRMSError", "LastTextureMB", "LastBricks")}
    report("target %(LastTargetMilliseconds)g ms, drawing's share %(LastDrawTargetMilliseconds).2f ms, predicted %(LastPredictedMilliseconds).2f ms, "
           "drawn %(LastDrawMilliseconds).2f ms, outcome '%(LastTimeOutcome)s', "
           "texture MB %(LastTextureMB).3f, bricks %(LastBricks)d, "
           "estimated RMS error %(LastEstimatedRMSError).5f" % s)
    return s


untimed = frame()
t.check(untimed["LastTargetMilliseconds"] == 0.0 and untimed["LastTimeOutcome"] == "",
        "untimed: no target, no outcome")
t.check(untimed["LastEstimatedRMSError"] > 0.0, "0.5 MB: an estimated RMS error above 0")

display.TargetFrameMilliseconds = 1.0e5
for i in range(WARM_UP):
    s = frame()
    t.check(s["LastTimeOutcome"] == "warm-up", "frame %d warms the cost model up" % i)
for i in range(2):
    s = frame()
    t.check(s["LastTimeOutcome"] == "full", "a 100 s target draws the full budget")
    t.check(s["LastTargetMilliseconds"] == 1.0e5, "the target is shown")
    t.check(1.0e4 <= s["LastDrawTargetMilliseconds"] < 1.0e5,
            "the drawing aims at the target less the view's time outside it")
    t.check(s["LastPredictedMilliseconds"] > 0.0 and s["LastDrawMilliseconds"] > 0.0,
            "predicted and measured times are shown")
    t.check(s["LastEstimatedRMSError"] == untimed["LastEstimatedRMSError"],
            "the full budget's estimated RMS error")
error = rmse(test.screenshot(view, "hybrid-full"), baseline)
report("100 s target: RMSE %.4f against ParaView's Volume (bound %.2f)" % (error, BOUND))
t.check(error <= BOUND, "100 s target: RMSE %.4f against ParaView's Volume" % error)

display.TargetFrameMilliseconds = 1.0e-3
for i in range(WARM_UP + 1):
    s = frame()
t.check(s["LastTimeOutcome"] == "below-fastest", "a 1 microsecond target is below the fastest frame")
t.check(s["LastEstimatedRMSError"] > untimed["LastEstimatedRMSError"],
        "the fastest frame pays a larger estimated RMS error")
t.check(s["LastBricks"] > 0, "the fastest frame draws")

display.TargetFrameMilliseconds = -5.0
s = frame()
t.check(s["LastBricks"] == 0, "a target of -5 ms draws nothing")
display.TargetFrameMilliseconds = 0.0
s = frame()
t.check(s["LastBricks"] > 0 and s["LastTimeOutcome"] == "", "untimed again, it draws")
t.finish()
