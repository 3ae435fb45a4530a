"""pvbatch test of the "Hybrid Octree Volume" representation.

    pvbatch test_representation.py --plugin <HybridOctree.so> --cli <hybrid-octree> --workdir <dir>

A 64^3 Shepp-Logan phantom written by the CLI is read with ParaView's own
reader (XMLImageDataReader) and drawn, in one render view, by:

- ParaView's "Volume" representation (vtkGPUVolumeRayCastMapper through
  vtkMultiBlockVolumeMapper), the baseline image;
- "Hybrid Octree Volume" at the default 64 MB budget: RMSE against the
  baseline at most 0.03 (RGB in [0, 1]; the two sample the same trilinear
  field at different positions, as in the mapper's gpu_reference test),
  and an Estimated Error of 0 (everything is drawn at full resolution);
- "Hybrid Octree Volume" at a 0.05 MB budget: its statistics stay within
  the budget, its Estimated Error is above 0 and its picture is further
  from the baseline;
- a drag: the view proxy's InteractiveRender() after a still frame draws
  the still frame's resident textures (0 bytes uploaded, the mapper's
  LastInteractive set), at full sampling the still picture (RMSE <= 0.002),
  at the sampling chosen for ParaView's allocated render time within RMSE
  0.04 of it; the next StillRender() is the full frame again (not
  interactive, full sampling, the still picture); with a translucent
  isosurface the drag's plan draws it per brick.

It also checks: the representation type is offered for image data and not
for an unstructured grid; reader -> Hybrid Octree filter -> the outlines of
its cut and an opaque sphere shown next to the volume, against the same
scene with ParaView's Volume representation (RMSE at most 0.03); the last-frame statistics; the plan with an
opaque and a translucent isosurface; hiding; a state file saved and loaded
keeps every Hybrid Octree property and the picture; a Python trace of the
pipeline replays to the same picture; a volume with NaN holes (no data)
draws without a message and shows the holes transparent; an infinite sample
and a zero budget give the mapper's clear error while pvbatch keeps
rendering.
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from paraview import servermanager, smtrace  # noqa: E402
from paraview.simple import *  # noqa: E402,F401,F403
from pvtest import Checks, generate_phantom, read_png_rgb, report, rmse, window_rgb  # noqa: E402
from representation_scene import SIZE, look_at, make_view, show_volume  # noqa: E402

parser = argparse.ArgumentParser()
parser.add_argument("--plugin", required=True)
parser.add_argument("--cli", required=True)
parser.add_argument("--workdir", required=True)
args = parser.parse_args()
os.makedirs(args.workdir, exist_ok=True)

t = Checks("HybridOctree representation test")
LoadPlugin(args.plugin, remote=False, ns=globals())
t.log_vtk_output(os.path.join(args.workdir, "vtk-output.txt"))

HYBRID = "Hybrid Octree Volume"
phantom_vti = generate_phantom(args.cli, args.workdir, 64)
reader = XMLImageDataReader(FileName=[phantom_vti])
reader.UpdatePipeline()
array = reader.PointData.keys()[0]
value_range = reader.PointData[array].GetRange()
bounds = reader.GetDataInformation().GetBounds()


def screenshot(view, name):
    path = os.path.join(args.workdir, name + ".png")
    SaveScreenshot(path, view, ImageResolution=list(SIZE))
    return read_png_rgb(path)


def stats(display):
    display.SMProxy.UpdatePropertyInformation()
    return {name: display.GetPropertyValue(name) for name in
            ("LastBricks", "LastTextureMB", "LastPlan", "LastFrameMilliseconds", "LastEstimatedError")}


# ---- Offered for image data only ---------------------------------------------------
view = make_view()
display = Show(reader, view)
t.check(HYBRID in display.GetProperty("Representation").Available,
        "'%s' offered for image data: %s" % (HYBRID, display.GetProperty("Representation").Available))
grid = Tetrahedralize(Input=Wavelet(WholeExtent=[0, 4, 0, 4, 0, 4]))
grid_display = Show(grid, view)
t.check(HYBRID not in grid_display.GetProperty("Representation").Available,
        "'%s' not offered for an unstructured grid" % HYBRID)
Hide(grid, view)
Hide(reader, view)
empty = screenshot(view, "empty")

# ---- Baseline: ParaView's own volume representation ---------------------------------
baseline_display = show_volume(reader, view, array, "Volume", value_range)
look_at(view, bounds)
baseline = screenshot(view, "baseline-volume")
t.check(rmse(baseline, empty) > 0.02, "the baseline shows the volume (RMSE to empty %.4f)" % rmse(baseline, empty))

# ---- Hybrid Octree Volume at the default budget -------------------------------------
display = show_volume(reader, view, array, HYBRID, value_range)
t.check(display.TextureBudgetMB == 64.0, "default budget 64 MB: %s" % display.TextureBudgetMB)
look_at(view, bounds)
full = screenshot(view, "hybrid-64MB")
error_full = rmse(full, baseline)
report("Hybrid Octree Volume, 64 MB: RMSE %.4f against ParaView's Volume representation" % error_full)
t.check(error_full <= 0.03, "64 MB: RMSE %.4f against the baseline (threshold 0.03)" % error_full)
s = stats(display)
report("statistics at 64 MB: %s" % s)
t.check(s["LastBricks"] > 0, "bricks drawn: %s" % s["LastBricks"])
t.check(0.0 < s["LastTextureMB"] <= 64.0, "texture MB within the budget: %s" % s["LastTextureMB"])
t.check(s["LastPlan"] == "volume", "plan 'volume': %r" % s["LastPlan"])
t.check(s["LastFrameMilliseconds"] > 0.0, "frame ms: %s" % s["LastFrameMilliseconds"])
# 64 MB holds the whole 64^3 phantom (1 MB of floats): every visible brick at full resolution.
t.check(s["LastEstimatedError"] == 0.0, "64 MB: estimated error 0, not %s" % s["LastEstimatedError"])

# ---- A drag: interactive frames from the still frame's resident textures -------------
import hybrid_octree  # noqa: E402,F401  (the mapper's class: its statistics)


def mapper_of(display):
    """The vtkHybridOctreeVolumeMapper behind a display (built-in session)."""
    return display.GetClientSideObject().GetActiveRepresentation().GetActor().GetMapper()


mapper = mapper_of(display)
view.SMProxy.StillRender()
still = window_rgb(view)
mapper.AutoAdjustSampleDistancesOff()
view.SMProxy.InteractiveRender()
t.check(mapper.GetLastInteractive() and mapper.GetLastRenderOK(), "InteractiveRender() is an interactive frame")
t.check(mapper.GetLastUploadedBytes() == 0, "the drag uploads nothing after a still frame: %d bytes"
        % mapper.GetLastUploadedBytes())
error_full_sampling = rmse(window_rgb(view), still)
t.check(error_full_sampling <= 0.002, "full sampling: the still picture (RMSE %.4f)" % error_full_sampling)
mapper.AutoAdjustSampleDistancesOn()
camera = view.GetActiveCamera()
uploaded = 0
for step in range(6):
    camera.Azimuth(5.0 if step < 3 else -5.0)
    view.SMProxy.InteractiveRender()
    uploaded += mapper.GetLastUploadedBytes()
    t.check(mapper.GetLastInteractive(), "drag frame %d is interactive" % step)
dragged = window_rgb(view)
sampling = (mapper.GetLastImageSampleDistance(), mapper.GetLastSampleSpacing())
report("drag: image sample distance %g, sample spacing %d d0, RMSE %.4f to the still picture (full sampling %.4f)"
       % (sampling[0], sampling[1], rmse(dragged, still), error_full_sampling))
t.check(uploaded == 0, "no upload while dragging: %d bytes" % uploaded)
# Measured at the coarsest sampling (image sample distance 6, samples every 2 d0): 0.026.
t.check(rmse(dragged, still) <= 0.04, "the drag's picture within RMSE 0.04 of the still one: %.4f"
        % rmse(dragged, still))
view.SMProxy.StillRender()
t.check(not mapper.GetLastInteractive() and mapper.GetLastImageSampleDistance() == 1.0
        and mapper.GetLastSampleSpacing() == 1, "the release is a still frame at full sampling")
t.check(mapper.GetLastUploadedBytes() == 0 and rmse(window_rgb(view), still) < 0.002,
        "the release draws the still picture from resident textures (RMSE %.4f)" % rmse(window_rgb(view), still))

# ---- A small budget: coarser bricks, within the budget, further from the baseline ----
display.TextureBudgetMB = 0.05
Render(view)
small = screenshot(view, "hybrid-0.05MB")
s_small = stats(display)
report("statistics at 0.05 MB: %s, RMSE %.4f" % (s_small, rmse(small, baseline)))
t.check(0.0 < s_small["LastTextureMB"] <= 0.05, "0.05 MB budget kept: %s MB" % s_small["LastTextureMB"])
t.check(s_small["LastEstimatedError"] > 0.0, "0.05 MB: an estimated error above 0: %s" % s_small["LastEstimatedError"])
t.check(rmse(small, baseline) > error_full, "a smaller budget is further from the baseline")
# ---- Hybrid points: paid from the same budget, drawn between the slices ---------------
display.HybridPoints = 1
display.PointFactor = 4
display.PointThreshold = 0.4
for footprint in ("Square", "Gaussian"):
    display.PointFootprint = footprint
    Render(view)
    with_points = screenshot(view, "hybrid-0.05MB-points-" + footprint.lower())
    display.SMProxy.UpdatePropertyInformation()
    s_points = stats(display)
    points = display.GetPropertyValue("LastPoints")
    report("%s points at 0.05 MB: %d drawn, %s; RMSE to 64 MB %.4f (without points %.4f)"
           % (footprint, points, s_points, rmse(with_points, full), rmse(small, full)))
    t.check(s_points["LastPlan"] == "volume,points", "plan with points: %r" % s_points["LastPlan"])
    t.check(points > 0, "%s points drawn: %d" % (footprint, points))
    t.check(0.0 < s_points["LastTextureMB"] <= 0.05, "textures within the budget: %s MB" % s_points["LastTextureMB"])
    t.check(rmse(with_points, small) > 0.001, "the points change the picture")
    # At equal bytes the points buy more than textures would here (measured
    # 0.0595 square, 0.0593 Gaussian, against 0.0640 without; docs/BENCHMARKS.md).
    t.check(rmse(with_points, full) <= 1.02 * rmse(small, full),
            "%s points: no further from the 64 MB picture than without them" % footprint)
# A point budget: at most that many points made, so at most that many drawn.
display.PointBudget = 500
Render(view)
display.SMProxy.UpdatePropertyInformation()
budgeted = display.GetPropertyValue("LastPoints")
report("Point Budget 500 at 0.05 MB: %d points drawn" % budgeted)
t.check(0 < budgeted <= 500, "Point Budget 500: %d points drawn" % budgeted)
display.PointBudget = 0
display.HybridPoints = 0
Render(view)
t.check(stats(display)["LastPlan"] == "volume", "points off: plan 'volume'")
display.TextureBudgetMB = 64.0

# ---- Isosurface: the planner's passes -------------------------------------------------
display.ShowIsosurface = 1
display.OctreeIsovalue = value_range[0] + 0.5 * (value_range[1] - value_range[0])
display.IsosurfaceOpacity = 0.5
Render(view)
t.check(stats(display)["LastPlan"] == "surface-in-slabs,volume",
        "translucent surface plan: %r" % stats(display)["LastPlan"])
view.SMProxy.InteractiveRender()
t.check(mapper.GetLastPlan() == "surface-per-brick,volume" and mapper.GetLastUploadedBytes() == 0,
        "a drag draws the translucent surface per brick from resident textures: %r" % mapper.GetLastPlan())
view.SMProxy.StillRender()
display.IsosurfaceOpacity = 1.0
Render(view)
surface_image = screenshot(view, "hybrid-opaque-surface")
t.check(stats(display)["LastPlan"] == "surface-opaque,volume",
        "opaque surface plan: %r" % stats(display)["LastPlan"])
t.check(rmse(surface_image, full) > 0.01, "the opaque surface changes the picture")
display.ShowIsosurface = 0

# ---- Next to ParaView's other representations ----------------------------------------
# reader -> Hybrid Octree filter -> the outlines of its cut (lines through the
# volume), and an opaque sphere cutting into the volume, in the same view:
# the volume must be hidden behind them and drawn in front of them exactly
# as ParaView's own Volume representation does.
octree = HybridOctree(Input=reader)
octree.Scalars = ["POINTS", array]
octree.ErrorTolerance = 0.05
boxes = Show(OutputPort(octree, 0), view)
boxes.ColorArrayName = ["POINTS", ""]
boxes.AmbientColor = boxes.DiffuseColor = [0.2, 0.9, 0.3]
extent = bounds[1] - bounds[0]
sphere = Sphere(Center=[bounds[0] + 0.3 * extent, bounds[3] - 0.3 * extent, 0.5 * (bounds[4] + bounds[5])],
                Radius=0.3 * extent,
                ThetaResolution=48, PhiResolution=48)
ball = Show(sphere, view)
ball.ColorArrayName = ["POINTS", ""]
ball.AmbientColor = ball.DiffuseColor = [0.9, 0.8, 0.3]
display.SetRepresentationType("Volume")
Render(view)
with_geometry_baseline = screenshot(view, "baseline-volume-with-geometry")
display.SetRepresentationType(HYBRID)
Render(view)
with_geometry = screenshot(view, "hybrid-with-geometry")
error_geometry = rmse(with_geometry, with_geometry_baseline)
report("with the filter's boxes and a sphere: RMSE %.4f against the Volume representation" % error_geometry)
t.check(rmse(with_geometry_baseline, baseline) > 0.01, "the boxes and the sphere show in the picture")
t.check(error_geometry <= 0.03, "with other representations: RMSE %.4f against the baseline (threshold 0.03)"
        % error_geometry)
Hide(OutputPort(octree, 0), view)
Hide(sphere, view)

# ---- Visibility -------------------------------------------------------------------------
Hide(reader, view)
hidden = screenshot(view, "hidden")
t.check(rmse(hidden, empty) < 1e-6, "hidden: only the background (RMSE %.6f)" % rmse(hidden, empty))
Show(reader, view)

# ---- State file: every Hybrid Octree property, and the picture ---------------------------
SETTINGS = {"TextureBudgetMB": 12.5, "InteractiveTextureBudgetMB": 3.25, "OctreeErrorTolerance": 0.02,
            "UseRegionOfInterest": 1, "RegionOfInterestCenter": [20.0, 30.0, 40.0],
            "RegionOfInterestRadius": 9.5, "ShowIsosurface": 1,
            "OctreeIsovalue": value_range[0] + 0.4 * (value_range[1] - value_range[0]),
            "IsosurfaceColor": [0.9, 0.6, 0.3], "IsosurfaceOpacity": 0.35, "OctreeLeafSize": 8,
            "TexelFormat": 2}
for name, value in SETTINGS.items():
    display.SetPropertyWithName(name, value)
Render(view)
before_state = screenshot(view, "before-state")
state_file = os.path.join(args.workdir, "hybrid.pvsm")
SaveState(state_file)
ResetSession()
LoadState(state_file)
loaded_view = GetActiveViewOrCreate("RenderView")
loaded_reader = FindSource("XMLImageDataReader1") or list(GetSources().values())[0]
loaded = GetDisplayProperties(loaded_reader, loaded_view)
t.check(loaded.Representation == HYBRID, "state keeps the representation type: %r" % loaded.Representation)


def numbers(proxy, name):
    """A property's values as numbers, whatever its domain (enumeration, boolean)."""
    helper = servermanager.vtkSMPropertyHelper(proxy.SMProxy, name)
    return [helper.GetAsDouble(i) for i in range(helper.GetNumberOfElements())]


for name, value in SETTINGS.items():
    expected = value if isinstance(value, list) else [value]
    got = numbers(loaded, name)
    t.check(len(got) == len(expected) and all(abs(a - b) < 1e-9 for a, b in zip(got, expected)),
            "state keeps %s: %r, saved %r" % (name, got, expected))
loaded_view.ViewSize = list(SIZE)
Render(loaded_view)
after_state = screenshot(loaded_view, "after-state")
t.check(rmse(after_state, before_state) < 0.002,
        "the loaded state draws the same picture (RMSE %.5f)" % rmse(after_state, before_state))

# ---- Python trace: record the pipeline as the GUI does, replay it ----------------------------
# The GUI's Apply wraps its property changes in a PropertiesModified trace
# item (pqProxyWidget); plain Python assignments are not traced.
def edit_as_gui(proxy, **values):
    item = smtrace.PropertiesModified(proxy)
    for name, value in values.items():
        proxy.SetPropertyWithName(name, value)
    item.finalize()


ResetSession()
smtrace.start_trace()
traced_reader = XMLImageDataReader(FileName=[phantom_vti])
traced_view = CreateView("RenderView")
edit_as_gui(traced_view, ViewSize=list(SIZE), OrientationAxesVisibility=0, UseColorPaletteForBackground=0,
            Background=[0.1, 0.1, 0.15])
traced = Show(traced_reader, traced_view)
traced.SetRepresentationType(HYBRID)
ColorBy(traced, ("POINTS", array))
lut = GetColorTransferFunction(array)
pwf = GetOpacityTransferFunction(array)
lo, hi = value_range
edit_as_gui(lut, RGBPoints=[lo, 0.2, 0.3, 0.8, hi, 0.9, 0.2, 0.1], AutomaticRescaleRangeMode="Never")
edit_as_gui(pwf, Points=[lo, 0.0, 0.5, 0.0, hi, 0.2, 0.5, 0.0])
edit_as_gui(traced, TextureBudgetMB=16.0, OctreeErrorTolerance=0.01, ShowIsosurface=1,
            OctreeIsovalue=lo + 0.5 * (hi - lo), IsosurfaceOpacity=0.6)
look_at(traced_view, bounds)
trace = smtrace.stop_trace()
with open(os.path.join(args.workdir, "trace.py"), "w") as f:
    f.write(trace)
traced_image = screenshot(traced_view, "traced")
for text in (HYBRID, "TextureBudgetMB = 16.0", "ShowIsosurface = 1", "IsosurfaceOpacity = 0.6"):
    t.check(text in trace, "the trace has %r" % text)
ResetSession()
exec(compile(trace, "trace.py", "exec"), {})
replay_view = GetActiveView()
Render(replay_view)
replayed = screenshot(replay_view, "replayed")
replayed_display = GetDisplayProperties(GetActiveSource(), replay_view)
t.check(replayed_display.TextureBudgetMB == 16.0, "replayed budget: %s" % replayed_display.TextureBudgetMB)
t.check(rmse(replayed, traced_image) < 0.002,
        "the replayed trace draws the same picture (RMSE %.5f)" % rmse(replayed, traced_image))

# ---- Bad input through ParaView: the mapper's error, and pvbatch keeps going ------------------
ResetSession()
import numpy as np  # noqa: E402  (pvbatch ships numpy)
from vtkmodules.util.numpy_support import numpy_to_vtk  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkImageData  # noqa: E402
from vtkmodules.vtkIOXML import vtkXMLImageDataWriter  # noqa: E402



def write_vti(values, n, name):
    """`values` (x fastest) as point scalars "f" of an n^3 image, written to the workdir."""
    img = vtkImageData()
    img.SetDimensions(n, n, n)
    scalars = numpy_to_vtk(values, deep=1)
    scalars.SetName("f")
    img.GetPointData().SetScalars(scalars)
    path = os.path.join(args.workdir, name)
    writer = vtkXMLImageDataWriter()
    writer.SetFileName(path)
    writer.SetInputData(img)
    writer.Write()
    return path


def draw(path, name):
    """The picture of the image at `path` in a new view, and what VTK logged meanwhile."""
    view = make_view()
    reader = XMLImageDataReader(FileName=[path])
    before = len(t.logged())
    show_volume(reader, view, "f", HYBRID, (0.0, 1.0))
    look_at(view, reader.GetDataInformation().GetBounds())
    return view, reader, screenshot(view, name), t.logged()[before:]


# NaN is no data: a ball of NaN in a bright cube draws without a message and
# is transparent: its picture is closer to that of a ball of 0 (transparent
# under the opacity) than to the cube without a hole (measured: 0.0051 and
# 0.0188; bound: half). Not equal: the NaN ball's boundary cells are
# dropped, the air ball's blend 0 with the cube.
N = 32
z, y, x = np.mgrid[0:N, 0:N, 0:N]
whole = (0.3 + 0.7 * x / (N - 1)).astype(np.float32).ravel()
ball = ((x - 16) ** 2 + (y - 16) ** 2 + (z - 16) ** 2 <= 81).ravel()
holed = whole.copy()
holed[ball] = np.nan
holed[(x < 2).ravel()] = np.nan
air = whole.copy()
air[ball] = 0.0
air[(x < 2).ravel()] = 0.0
_, _, whole_image, _ = draw(write_vti(whole, N, "whole.vti"), "whole")
_, _, air_image, _ = draw(write_vti(air, N, "air.vti"), "air")
bad_view, bad_reader, nan_image, new_output = draw(write_vti(holed, N, "nan.vti"), "nan")
t.check("ERROR" not in new_output,
        "NaN holes: no error in the output: %r" % new_output[-300:])
to_air, to_whole = rmse(nan_image, air_image), rmse(nan_image, whole_image)
report("NaN holes: RMSE %.4f against the air ball, %.4f against no hole" % (to_air, to_whole))
t.check(to_whole > 0.01, "the NaN holes show (RMSE %.4f against no hole)" % to_whole)
t.check(to_air < 0.5 * to_whole, "NaN holes are transparent: RMSE %.4f against the air ball, %.4f against no hole"
        % (to_air, to_whole))

# An infinite sample is an error: the mapper's message, nothing drawn.
infinite = whole.copy()
infinite[100] = np.inf
inf_view, inf_reader, inf_image, new_output = draw(write_vti(infinite, N, "inf.vti"), "inf")
t.check("1 infinite sample(s), the first at point index 100" in new_output,
        "infinite volume: the mapper's error in the output: %r" % new_output[-300:])
t.check(rmse(inf_image, screenshot(make_view(), "inf-empty")) < 1e-6, "infinite volume: nothing drawn")
Hide(inf_reader, inf_view)

good_reader = XMLImageDataReader(FileName=[phantom_vti])
zero = show_volume(good_reader, bad_view, array, HYBRID, value_range)
Hide(bad_reader, bad_view)
zero.TextureBudgetMB = 0.0
logged_before = len(t.logged())
Render(bad_view)
t.check("the texture budget is 0 MB" in t.logged()[logged_before:], "budget 0: the mapper's error")
zero.TextureBudgetMB = 64.0
Render(bad_view)
t.check(stats(zero)["LastBricks"] > 0, "after the errors pvbatch renders the phantom again")
Hide(good_reader, bad_view)

# ---- Texel formats: an 8-bit volume in 1 byte a texel, as Volume holds it ----------------
# The cube's ramp as 0..255 bytes (32^3): Texel Format Auto uploads R8 (Texture
# MB counts 1 byte a texel), Float32 four times the bytes and the same
# picture (measured RMSE 0.0011: 8-bit texels filter in 8 bits), and the
# picture is ParaView's Volume's (RMSE at most 0.03, as at 64 MB above; measured 0.0087).
u8_view = make_view()
u8_reader = XMLImageDataReader(FileName=[write_vti(np.round(whole * 255).astype(np.uint8), N, "u8.vti")])
u8 = show_volume(u8_reader, u8_view, "f", HYBRID, (0.0, 255.0))
# The data-space selection: the same bricks in both formats (a view's
# weights may split a brick differently when the texel error changes).
u8.ViewSelection = "Data"
look_at(u8_view, u8_reader.GetDataInformation().GetBounds())
Render(u8_view)
u8_auto = screenshot(u8_view, "u8-auto")
mb_auto = stats(u8)["LastTextureMB"]
u8.TexelFormat = 1
Render(u8_view)
mb_float = stats(u8)["LastTextureMB"]
same = rmse(screenshot(u8_view, "u8-float32"), u8_auto)
u8.TexelFormat = 0
u8.SetRepresentationType("Volume")
Render(u8_view)
to_volume = rmse(screenshot(u8_view, "u8-volume"), u8_auto)
report("8-bit volume: Texture MB %.4f (auto) and %.4f (float32) for %d voxels; RMSE %.4f to float32, %.4f to Volume"
       % (mb_auto, mb_float, N ** 3, same, to_volume))
t.check(N ** 3 / 1e6 <= mb_auto <= 1.1 * N ** 3 / 1e6, "auto: 1 byte a texel (%.4f MB)" % mb_auto)
t.check(abs(mb_float - 4 * mb_auto) < 1e-6, "float32: 4 bytes a texel (%.4f MB)" % mb_float)
t.check(same < 0.002, "8-bit texels draw the float32 picture (RMSE %.4f)" % same)
t.check(to_volume <= 0.03, "8-bit volume: RMSE %.4f against ParaView's Volume (threshold 0.03)" % to_volume)

t.finish()
