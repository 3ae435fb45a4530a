"""pvbatch test of volumetric scattering in the "Hybrid Octree Volume" representation.

    pvbatch test_scattering.py --plugin <HybridOctree.so> --cli <hybrid-octree> --workdir <dir>

The representation inherits VolumetricScatteringBlending and
GlobalIlluminationReach (forwarded to vtkHybridOctreeVolumeMapper by
vtkPVHybridOctreeRepresentation) and VolumeAnisotropy (the
vtkVolumeProperty's ScatteringAnisotropy) from ParaView's volume
representation. On a 64^3 Shepp-Logan phantom and a 64^3 Wavelet (smooth),
Shade on under the view's light kit, blending 1, reach 0.5, anisotropy 0.3:
ParaView's "Volume" representation against "Hybrid Octree Volume" at the
default budget, in 160^2 pictures, RMSE at most 0.03; the effects "shading,volume-scattering";
the scattering shows (RMSE above 0.01 against blending 0, whose effects are
"shading" only).
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from paraview.simple import Wavelet  # noqa: E402
from effect_test import EffectTest, statistic  # noqa: E402
from pvtest import Checks, report, rmse  # noqa: E402
from representation_scene import look_at, make_view, show_volume  # noqa: E402

test = EffectTest()
t = Checks("HybridOctree scattering test")
HYBRID = "Hybrid Octree Volume"
BOUND = 0.03
# Every sample casts shadow rays, in both representations: on llvmpipe a
# scattered 320^2 frame of the 64^3 Wavelet takes over a minute in
# *Volume*, so these pictures are drawn at a quarter of the other tests'
# pixels.
SIZE = (160, 160)


def scatter(display, blending):
    display.Shade = 1
    display.VolumetricScatteringBlending = blending
    display.GlobalIlluminationReach = 0.5
    display.VolumeAnisotropy = 0.3


wavelet = Wavelet(WholeExtent=[-32, 31, -32, 31, -32, 31])
wavelet.UpdatePipeline()
datasets = [
    ("phantom", test.reader, test.array, test.value_range, test.bounds),
    ("wavelet", wavelet, "RTData", wavelet.PointData["RTData"].GetRange(),
     wavelet.GetDataInformation().GetBounds()),
]
for name, source, array, value_range, bounds in datasets:
    view = make_view(SIZE)
    display = show_volume(source, view, array, "Volume", value_range)
    scatter(display, 1.0)
    look_at(view, bounds)
    baseline = test.screenshot(view, name + "-volume-scattered", SIZE)
    display.VolumetricScatteringBlending = 0.0
    unscattered_baseline = test.screenshot(view, name + "-volume-shaded", SIZE)
    display = show_volume(source, view, array, HYBRID, value_range)
    scatter(display, 0.0)
    look_at(view, bounds)
    shaded = test.screenshot(view, name + "-hybrid-shaded", SIZE)
    shaded_effects = statistic(display, "LastEffects")
    display.VolumetricScatteringBlending = 1.0
    scattered = test.screenshot(view, name + "-hybrid-scattered", SIZE)
    effects = statistic(display, "LastEffects")
    error = rmse(scattered, baseline)
    change = rmse(scattered, shaded)
    report("%s: RMSE %.4f against ParaView's scattered Volume (shaded: %.4f against its shaded Volume), "
           "scattering moves Volume by %.4f and Hybrid Octree Volume by %.4f"
           % (name, error, rmse(shaded, unscattered_baseline), rmse(baseline, unscattered_baseline), change))
    t.check(effects == "shading,volume-scattering", "%s: effects 'shading,volume-scattering': %r" % (name, effects))
    t.check(shaded_effects == "shading", "%s: blending 0: effects 'shading': %r" % (name, shaded_effects))
    t.check(error <= BOUND, "%s: RMSE %.4f against ParaView's scattered Volume (threshold %.2f)" % (name, error, BOUND))
    t.check(change > 0.01, "%s: the scattering shows: RMSE %.4f against blending 0" % (name, change))
t.finish()
