"""Interactive frames of the "Hybrid Octree Volume" representation against
ParaView's own "Volume", in one pvbatch process: the same scripted drag.

    PYTHONPATH=build/lib/python3.11/site-packages scripts/with-xvfb.sh \
        pvbatch bench/interactive_vs_volume.py \
        --plugin build/lib/paraview-5.11/plugins/HybridOctree/HybridOctree.so \
        --cli build/cargo/release/hybrid-octree \
        [--mri /work/data/mni_icbm152_t1_tal_nlin_sym_09a_converted.nii.gz] \
        [--phantom-size 256] [--steps 30] [--width 1130 --height 660] \
        [--stills 3] [--workdir DIR] [--json] [--check]

Data: a real 8-bit T1 MRI (--mri, NIfTI: ParaView 5.11 has no NIfTI
reader, so VTK's vtkNIFTIImageReader converts it to a .vti first, same
samples and spacing) and the CLI's built-in Shepp-Logan phantom at
--phantom-size^3 f32 (`hybrid-octree generate`), both read with
XMLImageDataReader.

Scene: a render view of --width x --height, ParaView's default colour map
and opacity ramp of the point array (what a first use in the GUI shows),
the camera reset on the data. Two scenes per dataset: the volume alone, and
with a translucent isosurface at mid-range, opacity 0.35: the
representation's own (ShowIsosurface 1, OctreeIsovalue, IsosurfaceOpacity
0.35) against a Contour filter shown as a Surface of the same opacity next
to ParaView's Volume (the view's default depth peeling).

Drag: --steps camera azimuth steps of 12 degrees (a whole turn at 30), each
drawn by the view proxy's InteractiveRender() (vtkPVRenderView sets the
window's desired update rate to 5 frames a second, as while the mouse drags
in the GUI), then StillRender() (the release). Timed: the wall time of each
call plus glFinish (the render window's WaitForCompletion). Before the drag
--stills still frames at the start view are timed (after one untimed
warm-up: octree build, uploads, shader compiles).

Printed: per dataset and scene, per representation the median, min and max
interactive frame ms, the median still frame ms, the ratio of the median to
Volume's (goal for ours: at most 1.0), the RMSE (RGB in [0, 1]) of the last
drag picture against the still picture of the same view (the release: what
the drag trades), and for ours the mapper's statistics of the drag (median
mapper ms against the allocated render time, image sample distance and
sample spacing chosen, bytes uploaded); peak RSS of the process. --json prints one JSON object per row. --check
(the CTest smoke run) fails unless every row is complete, our interactive
frames were marked interactive and uploaded no textures.
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

from paraview.simple import (ColorBy, Contour, CreateView, Delete, GetColorTransferFunction,  # noqa: E402
                             GetOpacityTransferFunction, Hide, LoadPlugin, Render, Show,
                             XMLImageDataReader)
from pvtest import Checks, generate_phantom, report, rmse, window_rgb  # noqa: E402

HYBRID = "Hybrid Octree Volume"
ISO_OPACITY = 0.35
STEP_DEGREES = 12.0

parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
parser.add_argument("--plugin", required=True, help="HybridOctree.so")
parser.add_argument("--cli", required=True, help="the hybrid-octree CLI")
parser.add_argument("--mri", default="/work/data/mni_icbm152_t1_tal_nlin_sym_09a_converted.nii.gz",
                    help="a NIfTI volume (none: skip)")
parser.add_argument("--phantom-size", type=int, default=256, help="phantom samples per axis (0 to skip)")
parser.add_argument("--steps", type=int, default=30, help="interactive frames of the drag")
parser.add_argument("--stills", type=int, default=3, help="timed still frames")
parser.add_argument("--width", type=int, default=1130)
parser.add_argument("--height", type=int, default=660)
parser.add_argument("--scenes", default="volume,isosurface", help="volume, isosurface or both")
parser.add_argument("--workdir", help="converted volumes and pictures (default: a temporary folder)")
parser.add_argument("--json", action="store_true", help="one JSON object per row instead of the table")
parser.add_argument("--check", action="store_true", help="fail unless every row is complete")
args = parser.parse_args()
workdir = args.workdir or tempfile.mkdtemp(prefix="interactive-vs-volume-")
os.makedirs(workdir, exist_ok=True)
started = time.perf_counter()
LoadPlugin(args.plugin, remote=False, ns=globals())


def nifti_as_vti(path):
    """The NIfTI file as a .vti in workdir (VTK's reader, same samples)."""
    from vtkmodules.vtkIOImage import vtkNIFTIImageReader
    from vtkmodules.vtkIOXML import vtkXMLImageDataWriter

    out = os.path.join(workdir, os.path.basename(path).split(".")[0] + ".vti")
    if not os.path.exists(out):
        reader = vtkNIFTIImageReader()
        reader.SetFileName(path)
        writer = vtkXMLImageDataWriter()
        writer.SetFileName(out)
        writer.SetInputConnection(reader.GetOutputPort())
        writer.Write()
    return out


def timed(view, interactive):
    """One frame of `view` (InteractiveRender or StillRender) to glFinish, ms."""
    t = time.perf_counter()
    if interactive:
        view.SMProxy.InteractiveRender()
    else:
        view.SMProxy.StillRender()
    view.GetRenderWindow().WaitForCompletion()
    return (time.perf_counter() - t) * 1e3


def mapper_of(display):
    """The vtkHybridOctreeVolumeMapper behind a display (built-in session)."""
    import hybrid_octree  # noqa: F401 (the mapper's Python class)

    return display.GetClientSideObject().GetActiveRepresentation().GetActor().GetMapper()


def run_row(dataset, path, scene, representation):
    view = CreateView("RenderView")
    view.ViewSize = [args.width, args.height]
    view.OrientationAxesVisibility = 0
    reader = XMLImageDataReader(FileName=[path])
    reader.UpdatePipeline()
    array = reader.PointData.keys()[0]
    lo, hi = reader.PointData[array].GetRange()
    display = Show(reader, view)
    display.SetRepresentationType(representation)
    ColorBy(display, ("POINTS", array))
    GetColorTransferFunction(array).RescaleTransferFunction(lo, hi)
    GetOpacityTransferFunction(array).RescaleTransferFunction(lo, hi)
    iso = lo + 0.5 * (hi - lo)
    contour = None
    if scene == "isosurface":
        if representation == HYBRID:
            display.ShowIsosurface = 1
            display.OctreeIsovalue = iso
            display.IsosurfaceOpacity = ISO_OPACITY
        else:
            contour = Contour(Input=reader, ContourBy=["POINTS", array], Isosurfaces=[iso])
            surface = Show(contour, view)
            surface.ColorArrayName = ["POINTS", ""]
            surface.Opacity = ISO_OPACITY
    Render(view)
    view.ResetCamera()
    camera = view.GetActiveCamera()
    camera.Elevation(20.0)
    camera.OrthogonalizeViewUp()
    view.ResetCamera()
    timed(view, False)  # warm-up: octree, uploads, shaders
    stills = [timed(view, False) for _ in range(args.stills)]
    name = os.path.join(workdir, "%s-%s-%s" % (dataset, scene, "hybrid" if representation == HYBRID else "volume"))
    window_rgb(view, name + "-still.png")
    mapper = mapper_of(display) if representation == HYBRID else None
    frames, uploads, flagged, levels = [], [], [], []
    for _ in range(args.steps):
        camera.Azimuth(STEP_DEGREES)
        frames.append(timed(view, True))
        if not mapper:
            continue
        uploads.append(mapper.GetLastUploadedBytes())
        flagged.append(bool(mapper.GetLastInteractive()))
        # (A build before the interactive path has no sampling statistics: 1, 1.)
        levels.append((getattr(mapper, "GetLastImageSampleDistance", lambda: 1.0)(),
                       getattr(mapper, "GetLastSampleSpacing", lambda: 1)(), mapper.GetLastFrameMilliseconds()))
    row = {"dataset": dataset, "scene": scene, "representation": representation,
           "median_ms": statistics.median(frames), "min_ms": min(frames), "max_ms": max(frames),
           "still_ms": statistics.median(stills), "frames": len(frames)}
    if mapper:
        row.update(bricks=mapper.GetLastBricks(), slices=mapper.GetLastSlices(),
                   mapper_ms=statistics.median(m for _, _, m in levels), uploaded=sum(uploads),
                   all_interactive=all(flagged), plan=mapper.GetLastPlan(),
                   image_sample_distance=statistics.median(s for s, _, _ in levels),
                   sample_spacing=statistics.median(m for _, m, _ in levels),
                   allocated_ms=1e3 * display.GetClientSideObject().GetActiveRepresentation()
                   .GetActor().GetAllocatedRenderTime())
    interactive_picture = window_rgb(view, name + "-drag.png")
    timed(view, False)  # the release: a still frame of the last drag view
    row["rmse_to_still"] = rmse(interactive_picture, window_rgb(view, name + "-release.png"))
    if mapper:
        row["still_interactive"] = bool(mapper.GetLastInteractive())
    Hide(reader, view)
    if contour:
        Hide(contour, view)
        Delete(contour)
    Delete(display)
    Delete(reader)
    Delete(view)
    return row


datasets = []
if args.mri != "none":
    datasets.append(("mri", nifti_as_vti(args.mri)))
if args.phantom_size > 0:
    datasets.append(("phantom", generate_phantom(args.cli, workdir, args.phantom_size)))
rows = []
for dataset, path in datasets:
    for scene in args.scenes.split(","):
        for representation in ("Volume", HYBRID):
            rows.append(run_row(dataset, path, scene, representation))
peak_mb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0

if args.json:
    for r in rows:
        report(json.dumps(r))
else:
    report("%dx%d, %d-step drag (%g degrees a step, InteractiveRender), %d still frames; ms to glFinish"
           % (args.width, args.height, args.steps, STEP_DEGREES, args.stills))
    report("| dataset | scene | representation | interactive median ms | min | max | still ms | x Volume "
           "| drag RMSE to still |")
    report("|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        base = next(b for b in rows if b["dataset"] == r["dataset"] and b["scene"] == r["scene"]
                    and b["representation"] == "Volume")
        report("| %s | %s | %s | %.1f | %.1f | %.1f | %.1f | %.2f | %.4f |" % (
            r["dataset"], r["scene"], r["representation"], r["median_ms"], r["min_ms"], r["max_ms"],
            r["still_ms"], r["median_ms"] / base["median_ms"], r["rmse_to_still"]))
    for r in rows:
        if "bricks" in r:
            report("  %s %s: %d bricks, plan '%s'; median of the drag: mapper %.1f ms (allocated %.1f ms), "
                   "image sample distance %g, sample spacing %g d0; %d bytes uploaded while dragging"
                   % (r["dataset"], r["scene"], r["bricks"], r["plan"], r["mapper_ms"], r["allocated_ms"],
                      r["image_sample_distance"], r["sample_spacing"], r["uploaded"]))
    report("peak RSS %.0f MB; %.1f s" % (peak_mb, time.perf_counter() - started))
if args.check:
    t = Checks("interactive_vs_volume")
    t.check(len(rows) == 2 * len(datasets) * len(args.scenes.split(",")), "%d rows" % len(rows))
    for r in rows:
        what = "%s %s %s" % (r["dataset"], r["scene"], r["representation"])
        t.check(0.0 < r["min_ms"] <= r["median_ms"] <= r["max_ms"] and r["still_ms"] > 0.0, what + ": times")
        if "bricks" in r:
            t.check(r["bricks"] > 0, what + ": bricks drawn")
            t.check(r["all_interactive"], what + ": every drag frame interactive")
            t.check(r["uploaded"] == 0, what + ": no uploads while dragging")
            t.check(not r["still_interactive"], what + ": the release is a still frame")
    t.finish()
# No sys.exit(): pvbatch 5.11 can crash in its teardown after one (pvtest.Checks.finish).
