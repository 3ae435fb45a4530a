"""One 512x512 frame of a 256^3 volume: our CPU compositor (`hybrid-octree
render`) against VTK's vtkFixedPointVolumeRayCastMapper, on the same machine
and the same scene.

    pvpython bench/render_vs_fixed_point.py --cli build/cargo/release/hybrid-octree \
        [--datasets shepp-logan,marschner-lobb] [--size 256] [--budgets 64,16] \
        [--repeats 5] [--outdir DIR]

Under Xvfb (VTK renders into an offscreen window of a real X display):

    scripts/with-xvfb.sh pvpython bench/render_vs_fixed_point.py --cli build/cargo/release/hybrid-octree

The scene is what `hybrid-octree render` sets up (src/bin/hybrid-octree/scene.rs):
the built-in dataset at `--size`^3 as f32 (written with `hybrid-octree
generate` and read back with vtkXMLImageDataReader for VTK), the transfer
function `TransferFunction::ramp(min, max)` over the data range
(src/render/transfer.rs: grey 0.3 to white, opacity 0 up to 15 % of the range
then 0.002, 0.03, 0.08, 0.12 at 20, 30, 60, 100 %, per reference spacing
d0 = min(spacing)), and the camera `Camera::around(lo, hi, 30, 20, false)`
(src/camera.rs: perspective, view angle 30, azimuth 30, elevation 20, looking
at the centre of the volume's box from 1.05 radius / sin(15 deg)).

VTK: vtkFixedPointVolumeRayCastMapper, trilinear interpolation, no shading,
one ray per pixel (ImageSampleDistance 1), samples every d0 along the ray
(SampleDistance d0, AutoAdjustSampleDistances off, so it never coarsens to
meet a frame-rate target), opacity unit distance d0 (the same opacity
correction as ours), in a 512x512 offscreen vtkRenderWindow. Timed: the wall
time of renderWindow.Render(), one untimed warm-up (the mapper converts the
scalars and builds its min-max volume then), then the median of --repeats;
the volume is marked modified before each render. The mapper re-casts every
ray on every Render() (its own GetTimeToDraw() is shown too, and a median
near 0 ms is refused as a render that did not happen).

Ours: `hybrid-octree render --dataset D --size N --width 512 --height 512
--output F.png --json`, one process per repeat, at each texture budget of
--budgets (64 MB is the CLI's default); the medians over the processes of
the reported composite_ms (the CPU compositor executing the DrawList), and of
total = select_ms + slab_polygons_ms + drawlist_ms + composite_ms (the whole
frame from a built octree; the octree build is paid once per volume and not
counted).
Timing is interleaved: each round renders one VTK frame, then runs one
process per budget, so that the machine's slow spells hit both sides alike.

Both sides get every core: VTK's SMP backend is switched to STDThread with the
thread limit at the core count, and the mapper's vtkMultiThreader uses them
all (use_all_cores from bench/side_by_side.py, called before anything is
built); rayon uses all cores for ours.

Goal: our CPU compositor renders a 512x512 frame of a 256^3 volume at the
default budget at least as fast as vtkFixedPointVolumeRayCastMapper
(composite_ms <= VTK's Render() median on every dataset; the total is shown
alongside). Both pictures (VTK's through vtkWindowToImageFilter + vtkPNGWriter,
over our background colour) are kept in --outdir, with their RMSE (RGB in
[0, 1]) so that a very different picture shows in the table. Times move
from run to run (more when something else is using the cores): quote the
ratios of one run, whose rounds are interleaved.
"""
import argparse
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np
from side_by_side import generated_image, use_all_cores
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkMultiThreader, vtkSMPTools
from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction
from vtkmodules.vtkIOImage import vtkPNGReader, vtkPNGWriter
from vtkmodules.vtkRenderingCore import (vtkColorTransferFunction, vtkRenderer, vtkRenderWindow, vtkVolume,
                                         vtkVolumeProperty, vtkWindowToImageFilter)
from vtkmodules.vtkRenderingVolume import vtkFixedPointVolumeRayCastMapper
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (the OpenGL render window)
import vtkmodules.vtkRenderingVolumeOpenGL2  # noqa: F401 (the ray cast image display helper)

# src/render/image.rs BACKGROUND: our PNGs are shown over it, so VTK's is too.
BACKGROUND = (0.32, 0.34, 0.43)
DEFAULT_BUDGET_MB = 64.0


def ramp(vmin, vmax):
    """TransferFunction::ramp(min, max) of src/render/transfer.rs: (colour
    points [(value, (r, g, b))], opacity points [(value, opacity)])."""
    if not (math.isfinite(vmin) and math.isfinite(vmax)):
        lo, hi = 0.0, 1.0
    else:
        lo, hi = (vmin, vmax) if vmin <= vmax else (vmax, vmin)
    fractions = [(0.0, 0.0), (0.15, 0.0), (0.2, 0.002), (0.3, 0.03), (0.6, 0.08), (1.0, 0.12)]
    colours = [(lo, (0.3, 0.3, 0.3)), (hi, (1.0, 1.0, 1.0))]
    opacities = [(lo + f * (hi - lo), a) for f, a in fractions]
    return colours, opacities


def camera_around(lo, hi, azimuth_deg, elevation_deg, parallel):
    """Camera::around of src/camera.rs: (position, focal point, view up,
    ("parallel", scale) or ("perspective", view angle in degrees))."""
    centre = [0.5 * (lo[a] + hi[a]) for a in range(3)]
    radius = 0.5 * math.sqrt(sum((hi[a] - lo[a]) ** 2 for a in range(3)))
    az, el = math.radians(azimuth_deg), math.radians(elevation_deg)
    direction = [math.sin(az) * math.cos(el), -math.cos(az) * math.cos(el), math.sin(el)]
    angle = 30.0
    distance = radius / math.sin(math.radians(angle) / 2.0) * 1.05
    position = [centre[a] + distance * direction[a] for a in range(3)]
    up = [0.0, 1.0, 0.0] if abs(math.cos(el)) < 1e-6 else [0.0, 0.0, 1.0]
    projection = ("parallel", radius * 1.05) if parallel else ("perspective", angle)
    return position, centre, up, projection


def look_around(renderer, bounds, azimuth_deg, elevation_deg=20.0, parallel=False):
    """Points `renderer`'s camera as Camera::around(lo, hi, azimuth,
    elevation, parallel) of src/camera.rs, lo and hi the first and last
    sample's world positions (GridShape::world), i.e. the image `bounds`."""
    position, focal, up, (kind, value) = camera_around(bounds[0::2], bounds[1::2], azimuth_deg, elevation_deg,
                                                       parallel)
    camera = renderer.GetActiveCamera()
    camera.SetPosition(*position)
    camera.SetFocalPoint(*focal)
    camera.SetViewUp(*up)
    if kind == "parallel":
        camera.ParallelProjectionOn()
        camera.SetParallelScale(value)
    else:
        camera.ParallelProjectionOff()
        camera.SetViewAngle(value)


def volume_property(image):
    """The ramp transfer function of `image`'s range as a vtkVolumeProperty:
    opacities per d0 = min spacing (ScalarOpacityUnitDistance), linear
    interpolation, no shading."""
    vmin, vmax = image.GetPointData().GetScalars().GetRange()
    colours, opacities = ramp(vmin, vmax)
    colour = vtkColorTransferFunction()
    for x, (r, g, b) in colours:
        colour.AddRGBPoint(x, r, g, b)
    opacity = vtkPiecewiseFunction()
    for x, a in opacities:
        opacity.AddPoint(x, a)
    prop = vtkVolumeProperty()
    prop.SetColor(colour)
    prop.SetScalarOpacity(opacity)
    prop.SetScalarOpacityUnitDistance(min(image.GetSpacing()))  # ramp opacities are per d0
    prop.SetInterpolationTypeToLinear()
    prop.ShadeOff()
    return prop


def vtk_scene(image, width, height):
    """The fixed-point ray cast scene of `image`: (render window, renderer,
    mapper, volume), not rendered yet."""
    d0 = min(image.GetSpacing())
    prop = volume_property(image)

    mapper = vtkFixedPointVolumeRayCastMapper()
    mapper.SetInputData(image)
    mapper.AutoAdjustSampleDistancesOff()
    mapper.LockSampleDistanceToInputSpacingOff()
    mapper.SetSampleDistance(d0)
    mapper.SetInteractiveSampleDistance(d0)
    mapper.SetImageSampleDistance(1.0)
    volume = vtkVolume()
    volume.SetMapper(mapper)
    volume.SetProperty(prop)

    renderer = vtkRenderer()
    renderer.AddVolume(volume)
    renderer.SetBackground(*BACKGROUND)
    look_around(renderer, image.GetBounds(), 30.0)
    renderer.ResetCameraClippingRange()  # the whole volume between the planes

    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(width, height)
    window.AddRenderer(renderer)
    return window, renderer, mapper, volume


class VtkFrame:
    """The fixed-point mapper's scene of `image`, rendered once (the warm-up:
    the mapper converts the scalars and builds its min-max volume)."""

    def __init__(self, image, width, height):
        self.window, _, self.mapper, self.volume = vtk_scene(image, width, height)
        self.window.Render()

    def render(self):
        """One timed frame: (Render() wall ms, the mapper's time to draw ms)."""
        self.volume.Modified()
        t = time.perf_counter()
        self.window.Render()
        return (time.perf_counter() - t) * 1e3, self.mapper.GetTimeToDraw() * 1e3

    def save(self, png):
        """Writes the window's last frame to `png` and closes the window."""
        grab = vtkWindowToImageFilter()
        grab.SetInput(self.window)
        grab.SetInputBufferTypeToRGB()
        grab.ReadFrontBufferOff()
        grab.Update()
        writer = vtkPNGWriter()
        writer.SetFileName(png)
        writer.SetInputConnection(grab.GetOutputPort())
        writer.Write()
        self.window.Finalize()


def render_ours(cli, dataset, size, width, height, budget_mb, png):
    """One `hybrid-octree render --json` process: its report."""
    out = subprocess.run([cli, "render", "--dataset", dataset, "--size", str(size), "--width", str(width),
                          "--height", str(height), "--budget-mb", f"{budget_mb:g}", "--output", png, "--json"],
                         check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def png_rgb(path):
    """An RGB PNG as floats in [0, 1], shape (pixels, 3)."""
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    rgb = vtk_to_numpy(reader.GetOutput().GetPointData().GetScalars())[:, :3]
    return rgb.astype(np.float64) / 255.0


def rmse(a_png, b_png):
    """RMSE of two same-size RGB PNGs (both read bottom row first by VTK)."""
    a, b = png_rgb(a_png), png_rgb(b_png)
    return float(np.sqrt(np.mean((a - b) ** 2))) if a.shape == b.shape else float("nan")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--cli", required=True)
    ap.add_argument("--datasets", default="shepp-logan,marschner-lobb")
    ap.add_argument("--size", type=int, default=256)
    ap.add_argument("--width", type=int, default=512)
    ap.add_argument("--height", type=int, default=512)
    ap.add_argument("--budgets", default="64,16", help="texture budgets in MB; 64 is the CLI's default")
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--outdir", help="where the pictures go (default: a new temporary folder, kept)")
    args = ap.parse_args()
    if args.repeats < 1:
        ap.error("--repeats must be at least 1")

    cores = use_all_cores()  # before VTK builds anything that takes its thread count
    outdir = args.outdir or tempfile.mkdtemp(prefix="render_vs_fixed_point_")
    os.makedirs(outdir, exist_ok=True)
    budgets = [float(b) for b in args.budgets.split(",")]

    rows = []
    vtk_threads = None
    med = statistics.median
    with tempfile.TemporaryDirectory() as tmp:
        for dataset in args.datasets.split(","):
            image = generated_image(args.cli, dataset, args.size, "f32", os.path.join(tmp, f"{dataset}.vti"))
            vtk = VtkFrame(image, args.width, args.height)
            vtk_threads = vtk.mapper.GetNumberOfThreads()
            pngs = {b: os.path.join(outdir, f"{dataset}-{args.size}-ours-{b:g}mb.png") for b in budgets}
            # Interleaved rounds: one VTK frame, then one process per budget, so
            # that the machine's slow spells hit both sides alike.
            vtk_runs, ours_runs = [], {b: [] for b in budgets}
            for _ in range(args.repeats):
                vtk_runs.append(vtk.render())
                for b in budgets:
                    ours_runs[b].append(render_ours(args.cli, dataset, args.size, args.width, args.height, b,
                                                    pngs[b]))
            vtk_ms = med(r[0] for r in vtk_runs)
            if vtk_ms < 1.0:
                raise RuntimeError(f"VTK renders in {vtk_ms:.3f} ms: the mapper did not re-render between repeats")
            vtk_png = os.path.join(outdir, f"{dataset}-{args.size}-vtk-fixed-point.png")
            vtk.save(vtk_png)
            del vtk, image
            for b in budgets:
                runs = ours_runs[b]
                rows.append(dict(dataset=dataset, vtk=vtk_ms, draw=med(r[1] for r in vtk_runs),
                                 comp=med(r["composite_ms"] for r in runs),
                                 total=med(r["select_ms"] + r.get("slab_polygons_ms", 0.0) + r["drawlist_ms"]
                                           + r["composite_ms"] for r in runs),
                                 budget=runs[-1]["budget_bytes"] / 1e6, texture=runs[-1]["texture_bytes"] / 1e6,
                                 bricks=runs[-1]["bricks"], rmse=rmse(vtk_png, pngs[b])))

    print(f"cores: {cores}, VTK SMP backend {vtkSMPTools.GetBackend()} "
          f"({vtkSMPTools.GetEstimatedNumberOfThreads()} threads), vtkMultiThreader limit "
          f"{vtkMultiThreader.GetGlobalMaximumNumberOfThreads()}, fixed-point mapper threads {vtk_threads}")
    print(f"{args.width}x{args.height} frame of a {args.size}^3 f32 volume, repeats {args.repeats}, medians")
    header = (f"{'dataset':<15} {'VTK ms':>8} {'VTK draw':>9} {'comp ms':>8} {'total ms':>9} {'budget MB':>10} "
              f"{'texture MB':>11} {'bricks':>7} {'comp/VTK':>9} {'total/VTK':>10} {'RMSE':>7}")
    print(header)
    for r in rows:
        print(f"{r['dataset']:<15} {r['vtk']:>8.1f} {r['draw']:>9.1f} {r['comp']:>8.1f} {r['total']:>9.1f} "
              f"{r['budget']:>10.1f} {r['texture']:>11.2f} {r['bricks']:>7} {r['comp'] / r['vtk']:>9.2f} "
              f"{r['total'] / r['vtk']:>10.2f} {r['rmse']:>7.4f}")
    print("VTK ms: wall time of renderWindow.Render() with vtkFixedPointVolumeRayCastMapper;")
    print("VTK draw: the mapper's own GetTimeToDraw() (the ray cast, without the window's work);")
    print("comp ms: our composite_ms (CPU compositor); total ms: select + drawlist + composite;")
    print("RMSE: VTK's picture against ours, RGB in [0, 1], both over the same background.")

    default = [r for r in rows if r["budget"] == DEFAULT_BUDGET_MB]
    if default:
        ok = all(r["comp"] <= r["vtk"] for r in default)
        ok_total = all(r["total"] <= r["vtk"] for r in default)
        each = lambda key: ", ".join(f"{r['dataset']} {r[key] / r['vtk']:.2f}" for r in default)  # noqa: E731
        print(f"{'PASS' if ok else 'MISS'}: our CPU compositor renders a {args.width}x{args.height} frame of a "
              f"{args.size}^3 volume at the default budget ({DEFAULT_BUDGET_MB:g} MB) at least as fast as "
              f"vtkFixedPointVolumeRayCastMapper (composite_ms / VTK ms: {each('comp')})")
        print(f"      whole frame, select + drawlist + composite: {'as fast' if ok_total else 'slower'} "
              f"(total ms / VTK ms: {each('total')})")
    else:
        print(f"no row at the default budget ({DEFAULT_BUDGET_MB:g} MB): add it to --budgets for the PASS/MISS line")
    print(f"pictures: {outdir}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
