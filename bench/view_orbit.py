"""The view-dependent selection in ParaView: an orbit of still frames per
View Selection of the "Hybrid Octree Volume" representation.

    PYTHONPATH=build/lib/python3.11/site-packages scripts/with-xvfb.sh \\
        pvbatch bench/view_orbit.py \\
        --plugin build/lib/paraview-5.11/plugins/HybridOctree/HybridOctree.so \\
        --cli build/cargo/release/hybrid-octree \\
        [--mri /work/data/mni_icbm152_t1_tal_nlin_sym_09a_converted.nii.gz] \\
        [--frames 36 --step 10] [--width 320 --height 320] [--workdir DIR] [--json]

Datasets: the CLI's 256^3 Shepp-Logan phantom (f32, `hybrid-octree
generate --dataset shepp-logan --size 256`) and, when --mri names one, an
8-bit MRI read with VTK's NIfTI reader (vtkNIFTIImageReader, written to a
.vti for ParaView's reader). The budget of each is the
bytes of the uniform stride-4 texture of its grid (`ceil((n - 1) / 4) + 1`
texels per axis, the texels of the data's own width: 4 bytes for f32, 1
for u8). Per dataset and View Selection (Data, Screen Space, Visibility,
Both; View Change 5 degrees, Smallest Texel 1 pixel), after one frame at
the starting view (not counted: it builds the octree or selects from the
previous row's resident textures), `--frames` still frames with the camera
turned `--step` degrees about the view up between them; per row:

- texture MB resident after the last frame;
- uploaded MB per frame (mean), also as % of the budget;
- selections made and the mean ms of one (the mapper's
  LastSelectMilliseconds over the frames that selected);
- mean frame ms (StillRender + glFinish);
- RMSE (RGB in [0, 1]) of the last frame against ParaView's *Volume*
  (vtkSmartVolumeMapper, which draws with vtkGPUVolumeRayCastMapper at
  full resolution) at the same view.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tests", "paraview"))

from paraview.simple import Delete, Hide, LoadPlugin, XMLImageDataReader  # noqa: E402
from pvtest import read_png_rgb, rmse, window_rgb  # noqa: E402
from representation_scene import look_at, make_view, show_volume  # noqa: E402

HYBRID = "Hybrid Octree Volume"
MODES = ["Data", "Screen Space", "Visibility", "Both"]
# Texel Format Auto's bytes by VTK type code: 8-bit 1, 16-bit 2, the rest 4 (R32F).
TEXEL_BYTES = {2: 1, 3: 1, 15: 1, 4: 2, 5: 2}


def parse():
    p = argparse.ArgumentParser()
    p.add_argument("--plugin", required=True)
    p.add_argument("--cli", required=True)
    p.add_argument("--mri", default=None)
    p.add_argument("--size", type=int, default=256)
    p.add_argument("--frames", type=int, default=36)
    p.add_argument("--step", type=float, default=10.0)
    p.add_argument("--width", type=int, default=320)
    p.add_argument("--height", type=int, default=320)
    p.add_argument("--workdir", default=None)
    p.add_argument("--json", action="store_true")
    return p.parse_args()


def statistic(display, name):
    display.SMProxy.UpdatePropertyInformation()
    return display.GetPropertyValue(name)


def stride4_bytes(reader, array):
    """Bytes of the uniform stride-4 texture of the reader's grid."""
    info = reader.GetDataInformation()
    extent = info.GetExtent()
    texels = 1
    for a in range(3):
        cells = extent[2 * a + 1] - extent[2 * a]
        texels *= -(-cells // 4) + 1
    return texels * TEXEL_BYTES.get(reader.PointData[array].GetDataType(), 4)


def frame(view):
    t = time.perf_counter()
    view.SMProxy.StillRender()
    view.GetRenderWindow().WaitForCompletion()
    return (time.perf_counter() - t) * 1e3


def orbit_rows(name, reader, args, workdir):
    array = reader.PointData.keys()[0]
    value_range = reader.PointData[array].GetRange()
    bounds = reader.GetDataInformation().GetBounds()
    budget = stride4_bytes(reader, array)
    view = make_view()
    view.ViewSize = [args.width, args.height]
    # The reference: ParaView's Volume at the orbit's last view.
    volume = show_volume(reader, view, array, "Volume", value_range)
    look_at(view, bounds)
    view.GetActiveCamera().Azimuth(args.step * args.frames)
    frame(view)
    reference_png = os.path.join(workdir, "%s-volume.png" % name)
    window_rgb(view, reference_png)
    reference = read_png_rgb(reference_png)
    Hide(reader, view)
    display = show_volume(reader, view, array, HYBRID, value_range)
    display.TextureBudgetMB = budget / 1e6
    display.ViewChangeDegrees = 5.0
    display.MinTexelPixels = 1.0
    rows = []
    for mode in MODES:
        display.ViewSelection = mode
        look_at(view, bounds)  # renders the uncounted first frame
        camera = view.GetActiveCamera()
        uploaded, select_ms, frame_ms = [], [], []
        for _ in range(args.frames):
            camera.Azimuth(args.step)
            frame_ms.append(frame(view))
            uploaded.append(statistic(display, "LastUploadedMB") * 1e6)
            if statistic(display, "LastReselected"):
                select_ms.append(statistic(display, "LastSelectMilliseconds"))
        png = os.path.join(workdir, "%s-%s.png" % (name, mode.replace(" ", "-").lower()))
        window_rgb(view, png)
        rows.append({
            "dataset": name, "view_selection": mode, "ran": statistic(display, "LastViewSelection"),
            "budget_bytes": budget, "texture_bytes": statistic(display, "LastTextureMB") * 1e6,
            "uploaded_mean_bytes": statistics.mean(uploaded),
            "uploaded_percent_of_budget": 100.0 * statistics.mean(uploaded) / budget,
            "selections": len(select_ms),
            "select_mean_ms": statistics.mean(select_ms) if select_ms else 0.0,
            "frame_mean_ms": statistics.mean(frame_ms),
            "rmse_vs_volume": rmse(read_png_rgb(png), reference),
        })
        print("  %s %-12s done" % (name, mode), file=sys.stderr, flush=True)
    Delete(display)
    Delete(volume)
    return rows


def nifti_to_vti(nifti, vti):
    """VTK's NIfTI reader (.nii, .nii.gz) into a .vti file (ParaView 5.11
    has no reader registered for .nii.gz)."""
    from vtkmodules.vtkIOImage import vtkNIFTIImageReader
    from vtkmodules.vtkIOXML import vtkXMLImageDataWriter

    reader = vtkNIFTIImageReader()
    reader.SetFileName(nifti)
    writer = vtkXMLImageDataWriter()
    writer.SetInputConnection(reader.GetOutputPort())
    writer.SetFileName(vti)
    writer.Write()


def main():
    args = parse()
    LoadPlugin(args.plugin, remote=False)
    workdir = args.workdir or tempfile.mkdtemp(prefix="ho-view-orbit-")
    os.makedirs(workdir, exist_ok=True)
    started = time.perf_counter()
    phantom = os.path.join(workdir, "phantom%d.vti" % args.size)
    subprocess.run([args.cli, "generate", "--dataset", "shepp-logan", "--size", str(args.size),
                    "--output", phantom], check=True, capture_output=True)
    rows = orbit_rows("phantom %d^3 f32" % args.size, XMLImageDataReader(FileName=[phantom]), args, workdir)
    if args.mri:
        mri = os.path.join(workdir, "mri.vti")
        nifti_to_vti(args.mri, mri)
        rows += orbit_rows("MRI u8", XMLImageDataReader(FileName=[mri]), args, workdir)
        os.remove(mri)
    os.remove(phantom)
    if args.json:
        print(json.dumps(rows, indent=1))
        return
    print("%d still frames %.0f degrees apart, %dx%d, budget = stride-4 uniform bytes; %.0f s in all"
          % (args.frames, args.step, args.width, args.height, time.perf_counter() - started))
    print("| dataset | view selection | ran | budget MB | texture MB | uploaded MB/frame (% budget) "
          "| selections | selection ms | frame ms | RMSE vs *Volume* |")
    print("| --- | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for r in rows:
        print("| %s | %s | %s | %.3f | %.3f | %.3f (%.0f %%) | %d | %.1f | %.1f | %.4f |" % (
            r["dataset"], r["view_selection"], r["ran"], r["budget_bytes"] / 1e6, r["texture_bytes"] / 1e6,
            r["uploaded_mean_bytes"] / 1e6, r["uploaded_percent_of_budget"], r["selections"],
            r["select_mean_ms"], r["frame_mean_ms"], r["rmse_vs_volume"]))


main()
