"""Frames within a time: the mapper's TargetFrameMilliseconds against VTK's
GPU ray caster with AutoAdjustSampleDistances at the same desired update
rate, on the same orbit, in one pvbatch process.

    PYTHONPATH=build/lib/python3.11/site-packages scripts/with-xvfb.sh \
        pvbatch bench/time_target.py \
        --plugin build/lib/paraview-5.11/plugins/HybridOctree/HybridOctree.so \
        --cli build/cargo/release/hybrid-octree \
        [--phantom-size 256] [--vti more.vti ...] [--targets-ms 50,100,200,400] \
        [--frames 24] [--size 512] [--budget-mb 64] [--workdir DIR] [--json] [--check]

Data: the CLI's Shepp-Logan phantom at --phantom-size^3 f32 (`hybrid-octree
generate`) and any --vti files (real 8- and 16-bit scans). Scenes: the
volume alone under a ramp opacity, and the same with a translucent
isosurface at mid-range (opacity 0.35: ours the mapper's own surface, VTK's
a vtkContourFilter actor beside the GPU ray caster).

Per dataset and scene, in plain VTK windows of --size^2 (the plugin's
Python module gives the mapper class):

- the reference: VTK's vtkGPUVolumeRayCastMapper, no adjustment, rays
  sampled every half of the smallest spacing, at each of --frames views of
  an orbit (360 / frames degrees apart);
- VTK auto: the same mapper with AutoAdjustSampleDistances on and the
  window's desired update rate 1000 / target (its allocated render time
  the target), two laps of the orbit, the second timed;
- ours: vtkHybridOctreeVolumeMapper with TargetFrameMilliseconds = target
  under a texture budget of --budget-mb, a still window (every frame timed
  by the mapper's cost model), two laps, the second timed (the first
  holds the warm-up).

Timed per frame: the window's Render() to glFinish (WaitForCompletion),
and for ours also the mapper's own drawing time (LastDrawMilliseconds, the
time the target is about), its prediction, the drawing's share of the
target (LastDrawTargetMilliseconds) and the search's time
(LastSelectMilliseconds, 0 when a frame kept its selection). RMSE: RGB in [0, 1] against
the reference picture of the same view. Printed per target: median and
90th percentile of the frame times against the target, median RMSE of
both, our median estimated RMS error; per dataset and scene, the Spearman
rank correlation of our estimated RMS error and our measured RMSE over all
frames, and our RMSE at VTK's measured median frame time (interpolated on
our targets' error-time curve) over VTK's RMSE. --check (the CTest smoke
run) fails unless every row is complete.
"""
import argparse
import json
import os
import resource
import statistics
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tests", "paraview"))

from paraview.simple import LoadPlugin  # noqa: E402
from pvtest import Checks, generate_phantom, report  # noqa: E402

ISO_OPACITY = 0.35

parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
parser.add_argument("--plugin", required=True, help="HybridOctree.so")
parser.add_argument("--cli", required=True, help="the hybrid-octree CLI")
parser.add_argument("--phantom-size", type=int, default=256, help="phantom samples per axis (0 to skip)")
parser.add_argument("--vti", action="append", default=[], help="a .vti volume (repeatable)")
parser.add_argument("--targets-ms", default="50,100,200,400")
parser.add_argument("--frames", type=int, default=24, help="views of the orbit")
parser.add_argument("--size", type=int, default=512, help="window pixels per side")
parser.add_argument("--budget-mb", type=float, default=64.0)
parser.add_argument("--scenes", default="volume,isosurface")
parser.add_argument("--workdir", help="generated volumes (default: a temporary folder)")
parser.add_argument("--json", action="store_true", help="one JSON object per row instead of the table")
parser.add_argument("--check", action="store_true", help="fail unless every row is complete")
args = parser.parse_args()
workdir = args.workdir or tempfile.mkdtemp(prefix="time-target-")
os.makedirs(workdir, exist_ok=True)
started = time.perf_counter()
LoadPlugin(args.plugin, remote=False)

import numpy as np  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402
from vtkmodules.vtkFiltersCore import vtkContourFilter  # noqa: E402
from vtkmodules.vtkIOXML import vtkXMLImageDataReader  # noqa: E402
from vtkmodules.vtkRenderingCore import (vtkActor, vtkColorTransferFunction, vtkPolyDataMapper,  # noqa: E402
                                         vtkRenderer, vtkRenderWindow, vtkVolume, vtkVolumeProperty,
                                         vtkWindowToImageFilter)
from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction  # noqa: E402
from vtkmodules.vtkRenderingVolume import vtkGPUVolumeRayCastMapper  # noqa: E402
import vtkmodules.vtkRenderingVolumeOpenGL2  # noqa: E402,F401
import vtkmodules.vtkRenderingOpenGL2  # noqa: E402,F401
import hybrid_octree  # noqa: E402


def spearman(pairs):
    """Spearman's rank correlation of (x, y) pairs (average ranks for ties)."""
    def ranks(values):
        order = sorted(range(len(values)), key=lambda i: values[i])
        r = [0.0] * len(values)
        i = 0
        while i < len(order):
            j = i
            while j + 1 < len(order) and values[order[j + 1]] == values[order[i]]:
                j += 1
            for k in range(i, j + 1):
                r[order[k]] = 0.5 * (i + j)
            i = j + 1
        return r
    if len(pairs) < 3:
        return float("nan")
    x, y = ranks([p[0] for p in pairs]), ranks([p[1] for p in pairs])
    return float(np.corrcoef(x, y)[0, 1])


class Stage:
    """A window, renderer and volume of `image` under a ramp opacity and a
    cool-warm colour map; the isosurface scene adds a translucent surface."""

    def __init__(self, image, mapper, scene, contour_actor=False):
        lo, hi = image.GetPointData().GetScalars().GetRange()
        self.window = vtkRenderWindow()
        self.window.SetSize(args.size, args.size)
        self.window.SetMultiSamples(0)
        self.renderer = vtkRenderer()
        self.renderer.SetBackground(0.32, 0.34, 0.43)
        self.window.AddRenderer(self.renderer)
        colour = vtkColorTransferFunction()
        colour.AddRGBPoint(lo, 0.23, 0.30, 0.75)
        colour.AddRGBPoint(0.5 * (lo + hi), 0.87, 0.87, 0.87)
        colour.AddRGBPoint(hi, 0.71, 0.02, 0.15)
        opacity = vtkPiecewiseFunction()
        opacity.AddPoint(lo, 0.0)
        opacity.AddPoint(hi, 0.6)
        prop = vtkVolumeProperty()
        prop.SetColor(colour)
        prop.SetScalarOpacity(opacity)
        prop.SetInterpolationTypeToLinear()
        self.volume = vtkVolume()
        mapper.SetInputData(image)
        self.volume.SetMapper(mapper)
        self.volume.SetProperty(prop)
        self.renderer.AddVolume(self.volume)
        iso = lo + 0.5 * (hi - lo)
        if scene == "isosurface" and contour_actor:
            contour = vtkContourFilter()
            contour.SetInputData(image)
            contour.SetValue(0, iso)
            surface = vtkPolyDataMapper()
            surface.SetInputConnection(contour.GetOutputPort())
            surface.ScalarVisibilityOff()
            actor = vtkActor()
            actor.SetMapper(surface)
            actor.GetProperty().SetOpacity(ISO_OPACITY)
            self.renderer.AddActor(actor)
            self.keep = (contour, surface, actor)
        elif scene == "isosurface":
            mapper.ShowSurfaceOn()
            mapper.SetIsovalue(iso)
            mapper.SetSurfaceOpacity(ISO_OPACITY)
        self.renderer.ResetCamera()
        camera = self.renderer.GetActiveCamera()
        camera.Elevation(20.0)
        camera.OrthogonalizeViewUp()
        self.renderer.ResetCamera()
        self.start = (camera.GetPosition(), camera.GetFocalPoint(), camera.GetViewUp())

    def view(self, i):
        """Camera at orbit view `i` of args.frames."""
        camera = self.renderer.GetActiveCamera()
        camera.SetPosition(*self.start[0])
        camera.SetFocalPoint(*self.start[1])
        camera.SetViewUp(*self.start[2])
        camera.Azimuth(360.0 * i / args.frames)
        self.renderer.ResetCameraClippingRange()

    def frame(self):
        """One Render() to glFinish, ms."""
        t = time.perf_counter()
        self.window.Render()
        self.window.WaitForCompletion()
        return (time.perf_counter() - t) * 1e3

    def rgb(self):
        grab = vtkWindowToImageFilter()
        grab.SetInput(self.window)
        grab.SetInputBufferTypeToRGB()
        grab.ReadFrontBufferOff()
        grab.ShouldRerenderOff()
        grab.Update()
        return vtk_to_numpy(grab.GetOutput().GetPointData().GetScalars()).astype(float) / 255.0

    def close(self):
        self.window.Finalize()


def rmse(a, b):
    return float(np.sqrt(((a - b) ** 2).mean()))


def reference(image, scene):
    gpu = vtkGPUVolumeRayCastMapper()
    gpu.AutoAdjustSampleDistancesOff()
    gpu.SetSampleDistance(0.5 * min(image.GetSpacing()))
    stage = Stage(image, gpu, scene, contour_actor=True)
    pictures = []
    for i in range(args.frames):
        stage.view(i)
        stage.frame()
        pictures.append(stage.rgb())
    stage.close()
    return pictures


def vtk_auto(image, scene, target, pictures):
    gpu = vtkGPUVolumeRayCastMapper()
    gpu.AutoAdjustSampleDistancesOn()
    stage = Stage(image, gpu, scene, contour_actor=True)
    stage.window.SetDesiredUpdateRate(1000.0 / target)
    times, errors = [], []
    for lap in range(2):
        for i in range(args.frames):
            stage.view(i)
            ms = stage.frame()
            if lap == 1:
                times.append(ms)
                errors.append(rmse(stage.rgb(), pictures[i]))
    stage.close()
    return {"frame_ms": times, "rmse": errors}


def ours(image, scene, target, pictures):
    mapper = hybrid_octree.vtkHybridOctreeVolumeMapper()
    mapper.SetBudgetMB(args.budget_mb)
    mapper.SetTargetFrameMilliseconds(target)
    stage = Stage(image, mapper, scene)
    times, draws, aims, searches, predicted, estimated, errors, outcomes = [], [], [], [], [], [], [], []
    for lap in range(2):
        for i in range(args.frames):
            stage.view(i)
            ms = stage.frame()
            if lap == 1:
                times.append(ms)
                draws.append(mapper.GetLastDrawMilliseconds())
                aims.append(mapper.GetLastDrawTargetMilliseconds())
                searches.append(mapper.GetLastSelectMilliseconds())
                predicted.append(mapper.GetLastPredictedMilliseconds())
                estimated.append(mapper.GetLastEstimatedRMSError())
                outcomes.append(mapper.GetLastTimeOutcome())
                errors.append(rmse(stage.rgb(), pictures[i]))
    stage.close()
    return {"frame_ms": times, "draw_ms": draws, "draw_target_ms": aims, "search_ms": searches, "predicted_ms": predicted, "estimated": estimated,
            "rmse": errors, "outcomes": outcomes}


def p90(values):
    return float(np.percentile(values, 90))


targets = [float(t) for t in args.targets_ms.split(",")]
datasets = []
if args.phantom_size > 0:
    datasets.append(("phantom%d" % args.phantom_size, generate_phantom(args.cli, workdir, args.phantom_size)))
for path in args.vti:
    datasets.append((os.path.basename(path).split(".")[0], path))
rows, summaries = [], []
for dataset, path in datasets:
    reader = vtkXMLImageDataReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    for scene in args.scenes.split(","):
        pictures = reference(image, scene)
        pairs, curve, vtk_points = [], [], []
        for target in targets:
            v = vtk_auto(image, scene, target, pictures)
            o = ours(image, scene, target, pictures)
            row = {"dataset": dataset, "scene": scene, "target_ms": target,
                   "vtk_median_ms": statistics.median(v["frame_ms"]), "vtk_p90_ms": p90(v["frame_ms"]),
                   "vtk_rmse": statistics.median(v["rmse"]),
                   "ours_median_ms": statistics.median(o["frame_ms"]), "ours_p90_ms": p90(o["frame_ms"]),
                   "ours_draw_median_ms": statistics.median(o["draw_ms"]), "ours_draw_p90_ms": p90(o["draw_ms"]),
                   "ours_draw_target_ms": statistics.median(o["draw_target_ms"]),
                   "ours_search_ms": statistics.median(o["search_ms"]),
                   "ours_predicted_ms": statistics.median(o["predicted_ms"]),
                   "ours_rmse": statistics.median(o["rmse"]),
                   "ours_estimated": statistics.median(o["estimated"]),
                   "outcomes": ",".join(sorted(set(o["outcomes"])))}
            rows.append(row)
            pairs += list(zip(o["estimated"], o["rmse"]))
            curve.append((row["ours_median_ms"], row["ours_rmse"]))
            vtk_points.append((row["vtk_median_ms"], row["vtk_rmse"]))
        curve.sort()
        ratios = []
        for ms, error in vtk_points:
            if curve[0][0] <= ms <= curve[-1][0] and error > 0:
                ratios.append(float(np.interp(ms, [c[0] for c in curve], [c[1] for c in curve])) / error)
        summaries.append({"dataset": dataset, "scene": scene, "spearman": spearman(pairs),
                          "rmse_ratio_at_vtk_time": ratios})
peak_mb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0

if args.json:
    for r in rows + summaries:
        report(json.dumps(r))
else:
    report("%d^2 pixels, %d-view orbit (second lap timed), budget %g MB; ms to glFinish; "
           "RMSE against VTK's GPU ray caster unadjusted" % (args.size, args.frames, args.budget_mb))
    report("| dataset | scene | target ms | VTK auto median / p90 ms | VTK RMSE | ours frame median / p90 ms "
           "| ours draw median / p90 ms | draw target | search ms | predicted | ours RMSE | estimated RMS error "
           "| outcomes |")
    report("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        report("| %s | %s | %g | %.1f / %.1f | %.4f | %.1f / %.1f | %.1f / %.1f | %.1f | %.1f | %.1f | %.4f | %.4f "
               "| %s |" % (
            r["dataset"], r["scene"], r["target_ms"], r["vtk_median_ms"], r["vtk_p90_ms"], r["vtk_rmse"],
            r["ours_median_ms"], r["ours_p90_ms"], r["ours_draw_median_ms"], r["ours_draw_p90_ms"],
            r["ours_draw_target_ms"], r["ours_search_ms"], r["ours_predicted_ms"], r["ours_rmse"], r["ours_estimated"], r["outcomes"]))
    for s in summaries:
        report("  %s %s: Spearman(estimated, RMSE) %.3f; our RMSE at VTK's median time / VTK's: %s"
               % (s["dataset"], s["scene"], s["spearman"],
                  ", ".join("%.2f" % x for x in s["rmse_ratio_at_vtk_time"]) or "no VTK time within ours"))
    report("peak RSS %.0f MB; %.1f s" % (peak_mb, time.perf_counter() - started))
if args.check:
    t = Checks("time_target")
    t.check(len(rows) == len(datasets) * len(args.scenes.split(",")) * len(targets), "%d rows" % len(rows))
    for r in rows:
        what = "%s %s %g ms" % (r["dataset"], r["scene"], r["target_ms"])
        t.check(r["vtk_median_ms"] > 0 and r["ours_median_ms"] > 0 and r["ours_draw_median_ms"] > 0, what + ": times")
        t.check("warm-up" not in r["outcomes"], what + ": the second lap is past the warm-up")
        t.check(r["ours_predicted_ms"] > 0, what + ": predictions")
    t.finish()
# No sys.exit(): pvbatch 5.11 can crash in its teardown after one (pvtest.Checks.finish).
