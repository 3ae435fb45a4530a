"""vtkHybridOctreeVolumeMapper against VTK's own volume mappers: a 36-frame
orbit at 512x512, in one pvbatch/pvpython process on one machine.

    PYTHONPATH=build/lib/python3.11/site-packages scripts/with-xvfb.sh \
        pvbatch bench/mapper_vs_vtk.py --cli build/cargo/release/hybrid-octree \
        [--datasets shepp-logan,marschner-lobb] [--size 256] [--frames 36] \
        [--width 512 --height 512] [--budget-mb 64] [--rmse-every 9] [--outdir DIR] [--json]

Scenes (per dataset, generated at --size^3 f32 by `hybrid-octree generate`):

- "volume": the transfer function of render_vs_fixed_point.py (ramp: grey to
  white, opacity 0 below 15 % of the range, per d0 = min spacing), no
  shading. Mappers: ours at --budget-mb (64 MB: the mapper's default),
  vtkGPUVolumeRayCastMapper, vtkSmartVolumeMapper and
  vtkFixedPointVolumeRayCastMapper, each at its own defaults (what a VTK
  user gets).
- "translucent-surface": the same volume with the isosurface at half the data
  range, colour (0.9, 0.75, 0.55), opacity 0.4. Ours draws it in the slabs;
  VTK: vtkGPUVolumeRayCastMapper plus a vtkFlyingEdges3D surface actor of the
  same isovalue, colour and opacity, with dual depth peeling
  (SetUseDepthPeeling(1), SetUseDepthPeelingForVolumes(1), VTK's default peel
  limits).

The camera of frame k is Camera::around(lo, hi, 30 + 10 k, 20) of
src/camera.rs (perspective, 30 degrees), so that the CLI can render the same
view. Every frame is a still frame (desired update rate 0.0001). Timed: the
wall time of renderWindow.Render() + WaitForCompletion() (glFinish) of each
frame after one untimed warm-up
frame (texture uploads, shader compiles); reported: median, min and max over
the orbit.

RMSE: RGB in [0, 1] over the same background, against the full-resolution
reference of the same view, the CPU reference ray caster of `hybrid-octree
render --reference` (every sample at full resolution, the surface hit by
rays), at every --rmse-every-th frame; the row's rmse is the mean over those
frames.

Goals, printed as PASS/MISS: at the default budget, at least 2x the
frame rate of the fastest VTK mapper with RMSE no worse than 1.5x that
mapper's; with the translucent isosurface, at least 5x the frame rate of dual
depth peeling at equal or lower RMSE. --json prints one JSON object per row
(mapper, scene, dataset, median_ms, min_ms, max_ms, rmse, frames) instead of
the table.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from render_vs_fixed_point import BACKGROUND, look_around, png_rgb, volume_property  # noqa: E402
from side_by_side import generated_image, use_all_cores  # noqa: E402

from hybrid_octree import vtkHybridOctreeVolumeMapper  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402
from vtkmodules.vtkFiltersCore import vtkFlyingEdges3D  # noqa: E402
from vtkmodules.vtkIOImage import vtkPNGWriter  # noqa: E402
from vtkmodules.vtkRenderingCore import (vtkActor, vtkPolyDataMapper, vtkRenderer,  # noqa: E402
                                         vtkRenderWindow, vtkVolume, vtkWindowToImageFilter)
from vtkmodules.vtkRenderingVolume import (vtkFixedPointVolumeRayCastMapper,  # noqa: E402
                                           vtkGPUVolumeRayCastMapper)
from vtkmodules.vtkRenderingVolumeOpenGL2 import vtkSmartVolumeMapper  # noqa: E402
import vtkmodules.vtkRenderingOpenGL2  # noqa: E402,F401 (the OpenGL render window)

SURFACE_RGB = (0.9, 0.75, 0.55)  # src/bin/hybrid-octree/scene.rs surface_colour
SURFACE_OPACITY = 0.4
ISO_FRACTION = 0.5


def isovalue(image):
    vmin, vmax = image.GetPointData().GetScalars().GetRange()
    return vmin + ISO_FRACTION * (vmax - vmin)


def make_mapper(name, image, budget_mb, surface):
    if name == "hybrid-octree":
        mapper = vtkHybridOctreeVolumeMapper()
        mapper.SetBudgetMB(budget_mb)
        if surface:
            mapper.ShowSurfaceOn()
            mapper.SetIsovalue(isovalue(image))
            mapper.SetSurfaceColor(*SURFACE_RGB)
            mapper.SetSurfaceOpacity(SURFACE_OPACITY)
    elif name in ("gpu-ray-cast", "gpu-ray-cast+dual-depth-peeling"):
        mapper = vtkGPUVolumeRayCastMapper()
    elif name == "smart":
        mapper = vtkSmartVolumeMapper()
    elif name == "fixed-point":
        mapper = vtkFixedPointVolumeRayCastMapper()
    else:
        raise ValueError(name)
    mapper.SetInputData(image)
    return mapper


_WINDOW = []


def shared_window(args):
    """The offscreen window all rows draw into, made on first use."""
    if not _WINDOW:
        window = vtkRenderWindow()
        window.SetOffScreenRendering(1)
        window.SetMultiSamples(0)
        window.SetAlphaBitPlanes(1)
        window.SetSize(args.width, args.height)
        window.SetDesiredUpdateRate(0.0001)
        _WINDOW.append(window)
    return _WINDOW[0]


class Scene:
    """One mapper's window: the volume, and for VTK's translucent-surface row
    the FlyingEdges surface actor with dual depth peeling."""

    def __init__(self, name, image, args, surface):
        self.mapper = make_mapper(name, image, args.budget_mb, surface)
        volume = vtkVolume()
        volume.SetMapper(self.mapper)
        volume.SetProperty(volume_property(image))
        self.renderer = vtkRenderer()
        self.renderer.SetBackground(*BACKGROUND)
        self.renderer.AddVolume(volume)
        if surface and name != "hybrid-octree":
            contour = vtkFlyingEdges3D()
            contour.SetInputData(image)
            contour.SetValue(0, isovalue(image))
            contour.ComputeNormalsOn()
            poly = vtkPolyDataMapper()
            poly.SetInputConnection(contour.GetOutputPort())
            poly.ScalarVisibilityOff()
            actor = vtkActor()
            actor.SetMapper(poly)
            actor.GetProperty().SetColor(*SURFACE_RGB)
            actor.GetProperty().SetOpacity(SURFACE_OPACITY)
            actor.GetProperty().SetAmbient(0.0)
            actor.GetProperty().SetDiffuse(1.0)
            actor.GetProperty().SetSpecular(0.0)
            self.renderer.AddActor(actor)
            self.renderer.SetUseDepthPeeling(1)
            self.renderer.SetUseDepthPeelingForVolumes(1)
        # One window for every row (pvbatch refuses new X windows after a few).
        self.window = shared_window(args)
        self.window.GetRenderers().RemoveAllItems()
        self.window.AddRenderer(self.renderer)
        self.bounds = image.GetBounds()

    def look(self, azimuth):
        look_around(self.renderer, self.bounds, azimuth)
        self.renderer.ResetCameraClippingRange()

    def render(self, azimuth):
        """One frame at `azimuth`: Render() wall ms."""
        self.look(azimuth)
        t = time.perf_counter()
        self.window.Render()
        self.window.WaitForCompletion()  # glFinish: the drawing, not only its submission
        return (time.perf_counter() - t) * 1e3

    def rgb(self):
        grab = vtkWindowToImageFilter()
        grab.SetInput(self.window)
        grab.SetInputBufferTypeToRGB()
        grab.ReadFrontBufferOff()
        grab.Update()
        return vtk_to_numpy(grab.GetOutput().GetPointData().GetScalars())[:, :3].astype(np.float64) / 255.0

    def save(self, png):
        grab = vtkWindowToImageFilter()
        grab.SetInput(self.window)
        grab.SetInputBufferTypeToRGB()
        grab.ReadFrontBufferOff()
        writer = vtkPNGWriter()
        writer.SetFileName(png)
        writer.SetInputConnection(grab.GetOutputPort())
        writer.Write()

    def close(self):
        self.window.RemoveRenderer(self.renderer)
        self.renderer.ReleaseGraphicsResources(self.window)


def reference(cli, dataset, args, azimuth, surface, outdir):
    """The CLI's full-resolution reference picture of the view (RGB floats)."""
    ref = os.path.join(outdir, f"{dataset}-{'surface' if surface else 'volume'}-az{azimuth:g}-reference.png")
    if not os.path.exists(ref):
        cmd = [cli, "render", "--dataset", dataset, "--size", str(args.size), "--width", str(args.width),
               "--height", str(args.height), "--azimuth", f"{azimuth:g}", "--elevation", "20",
               "--budget-mb", "1", "--output", os.path.join(outdir, "scratch.png"), "--reference", ref]
        if surface:
            cmd += ["--isovalue", repr(float(args.isovalues[dataset])), "--surface-opacity", f"{SURFACE_OPACITY:g}"]
        subprocess.run(cmd, check=True, capture_output=True, text=True)
    return png_rgb(ref)


def run_row(name, dataset, image, args, surface, outdir):
    scene = Scene(name, image, args, surface)
    scene.render(30.0)  # warm-up: uploads, shader compiles, the octree build
    times, errors = [], []
    for k in range(args.frames):
        azimuth = 30.0 + 10.0 * k
        times.append(scene.render(azimuth))
        if k % args.rmse_every == 0:
            picture = scene.rgb()
            ref = reference(args.cli, dataset, args, azimuth, surface, outdir)
            errors.append(float(np.sqrt(np.mean((picture - ref) ** 2))))
            if k == 0:
                scene.save(os.path.join(outdir, f"{dataset}-{'surface' if surface else 'volume'}-{name}.png"))
    row = dict(mapper=name, scene="translucent-surface" if surface else "volume", dataset=dataset,
               median_ms=statistics.median(times), min_ms=min(times), max_ms=max(times),
               rmse=float(np.mean(errors)), frames=len(times))
    if name == "hybrid-octree":
        m = scene.mapper
        row.update(bricks=m.GetLastBricks(), texture_mb=m.GetLastTextureBytes() / 1e6, plan=m.GetLastPlan(),
                   estimated_error=m.GetLastEstimatedError())
    scene.close()
    return row


def verdicts(rows):
    out = []
    for dataset in sorted({r["dataset"] for r in rows}):
        vol = [r for r in rows if r["dataset"] == dataset and r["scene"] == "volume"]
        ours = next((r for r in vol if r["mapper"] == "hybrid-octree"), None)
        theirs = [r for r in vol if r["mapper"] != "hybrid-octree"]
        if ours and theirs:
            fastest = min(theirs, key=lambda r: r["median_ms"])
            speedup = fastest["median_ms"] / ours["median_ms"]
            ratio = ours["rmse"] / fastest["rmse"] if fastest["rmse"] > 0 else float("inf")
            ok = speedup >= 2.0 and ratio <= 1.5
            out.append(f"{'PASS' if ok else 'MISS'}: {dataset} volume: {speedup:.2f}x the frame rate of the fastest "
                       f"VTK mapper ({fastest['mapper']}, goal 2x), RMSE {ours['rmse']:.4f} vs {fastest['rmse']:.4f} "
                       f"= {ratio:.2f}x (goal <= 1.5x)")
        srf = [r for r in rows if r["dataset"] == dataset and r["scene"] == "translucent-surface"]
        ours = next((r for r in srf if r["mapper"] == "hybrid-octree"), None)
        ddp = next((r for r in srf if r["mapper"] != "hybrid-octree"), None)
        if ours and ddp:
            speedup = ddp["median_ms"] / ours["median_ms"]
            ok = speedup >= 5.0 and ours["rmse"] <= ddp["rmse"]
            out.append(f"{'PASS' if ok else 'MISS'}: {dataset} translucent isosurface: {speedup:.2f}x the frame rate "
                       f"of dual depth peeling (goal 5x), RMSE {ours['rmse']:.4f} vs {ddp['rmse']:.4f} "
                       f"(goal: equal or lower)")
    return out


def check_rows(rows, args):
    """What is wrong with the rows (empty: nothing): every mapper and scene
    present, with finite positive times, min <= median <= max, and an RMSE
    in [0, 1]; our rows drew bricks."""
    problems = []
    scenes = 1 if args.no_surface else 2
    expected = len(args.datasets.split(",")) * (len(args.mappers.split(",")) + (2 if scenes == 2 else 0))
    if len(rows) != expected:
        problems.append(f"{len(rows)} rows, expected {expected}")
    for r in rows:
        for key in ("mapper", "scene", "median_ms", "min_ms", "max_ms", "rmse"):
            if key not in r:
                problems.append(f"row {r.get('mapper')} has no {key}")
        if not (0.0 < r["min_ms"] <= r["median_ms"] <= r["max_ms"] < 1e7):
            problems.append(f"{r['mapper']} {r['scene']}: times {r['min_ms']}, {r['median_ms']}, {r['max_ms']}")
        if not (0.0 <= r["rmse"] <= 1.0):
            problems.append(f"{r['mapper']} {r['scene']}: rmse {r['rmse']}")
        if r["mapper"] == "hybrid-octree" and not r.get("bricks", 0) > 0:
            problems.append(f"hybrid-octree {r['scene']}: no bricks drawn")
    return problems


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--cli", required=True)
    ap.add_argument("--datasets", default="shepp-logan,marschner-lobb")
    ap.add_argument("--size", type=int, default=256)
    ap.add_argument("--frames", type=int, default=36)
    ap.add_argument("--width", type=int, default=512)
    ap.add_argument("--height", type=int, default=512)
    ap.add_argument("--budget-mb", type=float, default=64.0, help="our texture budget (the mapper's default)")
    ap.add_argument("--rmse-every", type=int, default=9, help="RMSE against the reference every this many frames")
    ap.add_argument("--mappers", default="hybrid-octree,gpu-ray-cast,smart,fixed-point")
    ap.add_argument("--no-surface", action="store_true", help="skip the translucent-surface scene")
    ap.add_argument("--outdir", help="pictures and references (default: a new temporary folder, kept)")
    ap.add_argument("--json", action="store_true", help="one JSON object per row on stdout")
    ap.add_argument("--check", action="store_true",
                    help="exit non-zero unless every row is complete (the CTest smoke test)")
    args = ap.parse_args()
    if args.frames < 1 or args.rmse_every < 1:
        ap.error("--frames and --rmse-every must be at least 1")
    cores = use_all_cores()
    outdir = args.outdir or tempfile.mkdtemp(prefix="mapper_vs_vtk_")
    os.makedirs(outdir, exist_ok=True)
    rows = []
    args.isovalues = {}
    for dataset in args.datasets.split(","):
        image = generated_image(args.cli, dataset, args.size, "f32", os.path.join(outdir, f"{dataset}.vti"))
        args.isovalues[dataset] = isovalue(image)
        for name in args.mappers.split(","):
            rows.append(run_row(name, dataset, image, args, False, outdir))
        if not args.no_surface:
            for name in ("hybrid-octree", "gpu-ray-cast+dual-depth-peeling"):
                rows.append(run_row(name, dataset, image, args, True, outdir))
    if args.check:
        problems = check_rows(rows, args)
        for p in problems:
            print(f"CHECK FAILED: {p}", file=sys.stderr)
        if problems:
            sys.exit(1)
    if args.json:
        for r in rows:
            print(json.dumps(r))
        for line in verdicts(rows):
            print(line, file=sys.stderr)
        return
    print(f"{args.width}x{args.height}, {args.size}^3 f32, {args.frames}-frame orbit (10 degrees a frame), "
          f"cores {cores}; RMSE against the CPU full-resolution reference every {args.rmse_every} frames")
    print(f"{'dataset':<15} {'scene':<20} {'mapper':<32} {'median ms':>10} {'min ms':>8} {'max ms':>8} "
          f"{'fps':>6} {'RMSE':>8}")
    for r in rows:
        print(f"{r['dataset']:<15} {r['scene']:<20} {r['mapper']:<32} {r['median_ms']:>10.1f} {r['min_ms']:>8.1f} "
              f"{r['max_ms']:>8.1f} {1e3 / r['median_ms']:>6.2f} {r['rmse']:>8.4f}")
    for r in rows:
        if "bricks" in r:
            print(f"  hybrid-octree {r['dataset']} {r['scene']}: {r['bricks']} bricks, {r['texture_mb']:.1f} MB "
                  f"resident, plan '{r['plan']}', estimated error {r['estimated_error']:.4f}")
    for line in verdicts(rows):
        print(line)
    print(f"pictures and references: {outdir}")


if __name__ == "__main__":
    main()
