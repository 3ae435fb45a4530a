"""pvbatch test of the 2D transfer function in the "Hybrid Octree Volume" representation.

    pvbatch test_transfer2d.py --plugin <HybridOctree.so> --cli <hybrid-octree> --workdir <dir>

The representation inherits UseTransfer2D, UseGradientForTransfer2D (on by
default: the y axis is the gradient magnitude) and TransferFunction2D from
ParaView's volume representation (vtkImageVolumeRepresentation puts the
vtkPVTransferFunction2D's image into the vtkVolumeProperty and turns its
TF_2D mode on). A 64^3 Shepp-Logan phantom in one view, a TransferFunction2D
of two boxes built from Python (GetTransferFunction2D, Range, Boxes,
OutputDimensions): the soft tissue at low gradient and the bright structures
at high gradient. ParaView's "Volume" representation against "Hybrid Octree
Volume" at the default budget, with ParaView's default table of 10 x 10 and one
of 128 x 128: RMSE at most 0.03 (measured 0.0123 and 0.0154), the
effects "transfer-2d,sample-distance"; the picture differs from the 1D
transfer function's (RMSE above 0.01); UseTransfer2D off again: no effect,
the 1D picture (RMSE below 0.002).

VTK takes the 2D table's alpha uncorrected at its sample distance s
(vtkSmartVolumeMapper's still frames: 0.32 voxel here) and reads the row of
each sample's gradient magnitude (central differences one voxel apart,
|g| s_mean / (range / 4)): the mapper converts the alpha to its reference
spacing d0 and, as the table's rows alias on the phantom's one-voxel steps
at one sample a voxel, slices at VTK's s (src/plan/sampling.rs). Measured at
one slice a voxel: 0.044; VTK's own picture at s = 1 voxel is 0.13 from its
picture at 0.32, and 0.018 between 0.316 and 0.317 (the lattice's phase
alone). Without the alpha conversion the RMSE is 0.139. VTK draws the
table resized to its texture (vtkImageResize to 1024 x 1024: Lanczos, the
corner texels' centres kept), and the mapper reads the same texels: reading
the 10 x 10 table itself measured 0.0176.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from paraview.simple import *  # noqa: E402,F401,F403
from effect_test import EffectTest, statistic  # noqa: E402
from pvtest import Checks, report, rmse  # noqa: E402
from representation_scene import look_at, make_view, show_volume  # noqa: E402

test = EffectTest()
t = Checks("HybridOctree 2D transfer function test")
HYBRID = "Hybrid Octree Volume"
args, reader, array = test.args, test.reader, test.array
value_range, bounds = test.value_range, test.bounds
lo, hi = value_range
w = hi - lo
# VTK's axes: x the data range, y the gradient magnitude per mean spacing
# over [0, range / 4] (the image's own Range only places the boxes).
g = 0.25 * w
tf2d = GetTransferFunction2D(array)
tf2d.Range = [lo, hi, 0.0, g]
# Boxes (x, y, width, height, r, g, b, a): soft tissue at low gradient,
# the bright structures and the skull at high gradient.
tf2d.Boxes = [lo + 0.12 * w, 0.0, 0.36 * w, 0.12 * g, 0.95, 0.75, 0.45, 0.08,
              lo + 0.45 * w, 0.08 * g, 0.55 * w, 0.92 * g, 0.35, 0.6, 1.0, 0.5]


screenshot = test.screenshot


def effects(display):
    return statistic(display, "LastEffects")


def use_2d(display, on):
    display.UseTransfer2D = 1 if on else 0
    display.UseGradientForTransfer2D = 1
    display.TransferFunction2D = tf2d


view = make_view()
display = None
# ParaView's default table (10 x 10) and a finer one: VTK draws either resized
# to its 1024 x 1024 texture, and so does the mapper.
for dims in ([10, 10], [128, 128]):
    tf2d.OutputDimensions = dims
    if display is not None:
        Hide(display, view)
    baseline_display = show_volume(reader, view, array, "Volume", value_range)
    use_2d(baseline_display, True)
    look_at(view, bounds)
    baseline = screenshot(view, "transfer2d-volume-%d" % dims[0])
    display = show_volume(reader, view, array, HYBRID, value_range)
    use_2d(display, False)
    look_at(view, bounds)
    one_d = screenshot(view, "hybrid-1d-%d" % dims[0])
    t.check(effects(display) == "", "1D: no effect: %r" % effects(display))
    use_2d(display, True)
    two_d = screenshot(view, "hybrid-transfer2d-%d" % dims[0])
    error = rmse(two_d, baseline)
    change = rmse(two_d, one_d)
    report("2D transfer function of %d x %d: RMSE %.4f against ParaView's Volume, %.4f against the 1D picture"
           % (dims[0], dims[1], error, change))
    t.check(effects(display) == "transfer-2d,sample-distance",
            "effects 'transfer-2d,sample-distance': %r" % effects(display))
    t.check(error <= 0.03, "%d x %d: RMSE %.4f against ParaView's Volume with the 2D transfer function "
            "(threshold 0.03)" % (dims[0], dims[1], error))
    t.check(change > 0.01, "the 2D transfer function shows: RMSE %.4f against the 1D picture" % change)
    use_2d(display, False)
    again = screenshot(view, "hybrid-1d-again-%d" % dims[0])
    t.check(effects(display) == "", "UseTransfer2D off: no effect: %r" % effects(display))
    t.check(rmse(again, one_d) < 0.002, "UseTransfer2D off: the 1D picture (RMSE %.4f)" % rmse(again, one_d))
t.finish()
