"""The scale benchmark in ParaView: "Hybrid Octree Volume" against ParaView's
own "Volume" as the volume grows, each case in a pvbatch process of its own
(so that each peak RSS is that representation's alone).

    PYTHONPATH=build/lib/python3.11/site-packages scripts/with-xvfb.sh \
        pvbatch bench/scale.py \
        --plugin build/lib/paraview-5.11/plugins/HybridOctree/HybridOctree.so \
        --cli build/cargo/release/hybrid-octree \
        [--sizes 256,512,1024,2048x2048x1024] [--types u8,u16] [--dataset vessels] \
        [--frames 5] [--width 512 --height 512] [--budget-mb 64] [--workdir DIR] [--json] \
        [--view-selections Both,Data]

Per size (N: a cube; XxYxZ: a box) and scalar type the CLI writes the
built-in dataset to a .vti file (`hybrid-octree generate`, slab by slab),
then for each representation
one pvbatch process (this script with --case):

- read: XMLImageDataReader's UpdatePipeline, ms and the step's peak RSS;
- first frame: the representation shown, coloured, its first still frame
  (for the Hybrid Octree the octree build, the selection and the uploads),
  ms and peak RSS;
- orbit: --frames still frames, the camera turned 360 / frames degrees
  about the view up between them (for the Hybrid Octree each a new view,
  the selection kept), the median and the largest frame ms;
- the process's peak RSS, also as a multiple of the volume's bytes, and
  its RSS after each orbit frame (whether it still grows).

The Hybrid Octree has one row per --view-selections entry (the
representation's View Selection: Data, Screen Space, Visibility, Both; by
default its default alone), each in a process of its own.

A step's peak RSS is VmHWM after resetting it (`/proc/self/clear_refs`).
Frames are StillRender + glFinish. The last orbit picture of each
representation is kept, and the RMSE (RGB in [0, 1]) of ours against
*Volume*'s is printed where *Volume* drew. A case that fails (out of
memory, a texture too large, a crash) is a row with its exit status and
its last error line, not an omission; a picture of the background
alone is marked "drew nothing" (no RMSE is taken against it). Time per voxel is each step's ms
over the voxel count. The .vti files are removed at the end.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tests", "paraview"))

HYBRID = "Hybrid Octree Volume"
VOLUME = "Volume"
BYTES = {"u8": 1, "i8": 1, "u16": 2, "i16": 2, "f32": 4}


def parse():
    p = argparse.ArgumentParser()
    p.add_argument("--plugin", required=True)
    p.add_argument("--cli", required=True)
    p.add_argument("--sizes", default="256,512,1024")
    p.add_argument("--types", default="u8,u16")
    p.add_argument("--dataset", default="vessels")
    p.add_argument("--frames", type=int, default=5)
    p.add_argument("--width", type=int, default=512)
    p.add_argument("--height", type=int, default=512)
    p.add_argument("--budget-mb", type=float, default=64.0)
    p.add_argument("--workdir", default=None)
    p.add_argument("--json", action="store_true")
    p.add_argument("--view-selections", default="", help="View Selection per Hybrid Octree row, comma-separated "
                   "(Data, Screen Space, Visibility, Both); empty: the representation's default")
    p.add_argument("--view-selection", default="", help=argparse.SUPPRESS)
    # One case (internal): the file, the representation, the picture's path.
    p.add_argument("--case", default=None)
    p.add_argument("--representation", default=VOLUME)
    p.add_argument("--png", default=None)
    return p.parse_args()


def reset_peak():
    """Resets the process's VmHWM to its current RSS (Linux)."""
    try:
        with open("/proc/self/clear_refs", "w") as f:
            f.write("5")
    except OSError:
        pass


def status_bytes(field):
    """A size field of /proc/self/status (VmHWM: peak RSS, VmRSS: RSS), in bytes."""
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith(field + ":"):
                return int(line.split()[1]) * 1024
    return 0


def peak_bytes():
    return status_bytes("VmHWM")


def rss_bytes():
    return status_bytes("VmRSS")


def run_case(args):
    """One representation on one file, in this process: prints one JSON line."""
    from paraview.simple import LoadPlugin, XMLImageDataReader
    from representation_scene import look_at, make_view, show_volume
    from pvtest import window_rgb

    out = {"representation": args.representation}
    reset_peak()
    t = time.perf_counter()
    reader = XMLImageDataReader(FileName=[args.case])
    reader.UpdatePipeline()
    out["read_ms"] = (time.perf_counter() - t) * 1e3
    out["read_peak_bytes"] = peak_bytes()
    array = reader.PointData.keys()[0]
    value_range = reader.PointData[array].GetRange()
    bounds = reader.GetDataInformation().GetBounds()
    if args.representation == HYBRID:
        LoadPlugin(args.plugin, remote=False)
    view = make_view()
    view.ViewSize = [args.width, args.height]
    reset_peak()
    t = time.perf_counter()
    display = show_volume(reader, view, array, args.representation, value_range)
    if args.representation == HYBRID:
        display.TextureBudgetMB = args.budget_mb
        if args.view_selection:
            display.ViewSelection = args.view_selection
    look_at(view, bounds)  # renders: the first frame
    view.GetRenderWindow().WaitForCompletion()
    out["first_frame_ms"] = (time.perf_counter() - t) * 1e3
    out["first_frame_peak_bytes"] = peak_bytes()
    reset_peak()
    frames = []
    out["orbit_rss_bytes"] = []
    camera = view.GetActiveCamera()
    for _ in range(args.frames):
        camera.Azimuth(360.0 / max(args.frames, 1))
        t = time.perf_counter()
        view.SMProxy.StillRender()
        view.GetRenderWindow().WaitForCompletion()
        frames.append((time.perf_counter() - t) * 1e3)
        out["orbit_rss_bytes"].append(rss_bytes())
    out["frame_median_ms"] = statistics.median(frames)
    out["frame_max_ms"] = max(frames)
    out["orbit_peak_bytes"] = peak_bytes()
    window_rgb(view, args.png)
    if args.representation == HYBRID:
        display.SMProxy.UpdatePropertyInformation()
        out["bricks"] = display.GetPropertyValue("LastBricks")
        out["texture_mb"] = display.GetPropertyValue("LastTextureMB")
        out["estimated_error"] = display.GetPropertyValue("LastEstimatedError")
        out["view_selection_ran"] = display.GetPropertyValue("LastViewSelection")
    import resource
    out["process_peak_bytes"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
    print("CASE " + json.dumps(out), flush=True)


def spawn(args, path, representation, png, view_selection=""):
    """Runs one case in a new pvbatch; its row, or a failure row."""
    command = [sys.executable if os.path.basename(sys.executable).startswith("pv") else "pvbatch",
               os.path.abspath(__file__), "--plugin", args.plugin, "--cli", args.cli, "--case", path,
               "--representation", representation, "--png", png, "--frames", str(args.frames),
               "--width", str(args.width), "--height", str(args.height), "--budget-mb", str(args.budget_mb),
               "--view-selection", view_selection]
    done = subprocess.run(command, capture_output=True, text=True)
    for line in done.stdout.splitlines():
        if line.startswith("CASE "):
            return json.loads(line[len("CASE "):])
    errors = [x for x in (done.stderr + done.stdout).splitlines() if x.strip()]
    return {"representation": representation, "view_selection": view_selection, "failed": "exit status %d: %s"
            % (done.returncode, errors[-1][:200] if errors else "no output")}


def main():
    args = parse()
    if args.case:
        run_case(args)
        return
    from pvtest import read_png_rgb, rmse
    import tempfile

    workdir = args.workdir or tempfile.mkdtemp(prefix="ho-scale-")
    os.makedirs(workdir, exist_ok=True)
    rows = []
    for size in args.sizes.split(","):
        dims = [int(d) for d in size.split("x")] if "x" in size else [int(size)] * 3
        for ty in args.types.split(","):
            path = os.path.join(workdir, "%s-%s-%s.vti" % (args.dataset, size, ty))
            t = time.perf_counter()
            subprocess.run([args.cli, "generate", "--dataset", args.dataset, "--dims", ",".join(map(str, dims)),
                            "--type", ty, "--output", path], check=True, capture_output=True)
            generate_ms = (time.perf_counter() - t) * 1e3
            voxels = dims[0] * dims[1] * dims[2]
            volume_bytes = voxels * BYTES[ty]
            pictures = {}
            volume_row = None
            cases = [(VOLUME, "")] + [(HYBRID, v.strip()) for v in (args.view_selections or "").split(",")]
            for representation, view_selection in cases:
                png = os.path.join(workdir, "%s-%s-%s-%s%s.png" % (args.dataset, size, ty,
                                                                   representation.replace(" ", "-"),
                                                                   view_selection.replace(" ", "-")))
                row = spawn(args, path, representation, png, view_selection)
                row.setdefault("view_selection", view_selection)
                row.update(size=size, scalar_type=ty, volume_bytes=volume_bytes, generate_ms=generate_ms)
                for step in ("read", "first_frame", "frame_median"):
                    if step + "_ms" in row:
                        row[step + "_ns_per_voxel"] = row[step + "_ms"] * 1e6 / voxels
                if "process_peak_bytes" in row:
                    row["peak_ratio"] = row["process_peak_bytes"] / volume_bytes
                if "failed" not in row and os.path.exists(png):
                    picture = read_png_rgb(png)
                    # A picture of one colour drew nothing (the background): a failure too.
                    row["blank"] = bool(picture.std(axis=0).max() < 1e-3)
                    if representation == VOLUME:
                        pictures[VOLUME], volume_row = picture, row
                    elif VOLUME in pictures and not volume_row["blank"]:
                        row["rmse_vs_volume"] = rmse(picture, pictures[VOLUME])
                rows.append(row)
            os.remove(path)
    if args.json:
        print(json.dumps(rows, indent=1))
        return
    print("%s, %dx%d, %d orbit frames, budget %.0f MB; ms, peak RSS MB (x the volume's bytes)"
          % (args.dataset, args.width, args.height, args.frames, args.budget_mb))
    print("| size | type | representation | view selection | read ms | first frame ms | median frame ms | max frame ms "
          "| read peak MB | first-frame peak MB | orbit peak MB | process peak MB (x volume) "
          "| RSS after each orbit frame MB | first frame ns/voxel | RMSE vs Volume |")
    print("| ---: | --- | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- | ---: | ---: |")
    for r in rows:
        if "failed" in r:
            print("| %s | %s | %s | %s | failed: %s |" % (r["size"], r["scalar_type"], r["representation"],
                                                     r["view_selection"], r["failed"]))
            continue
        ran = r.get("view_selection_ran", "")
        print("| %s | %s | %s | %s | %.0f | %.0f | %.0f | %.0f | %.0f | %.0f | %.0f | %.0f (%.2fx) | %s | %.2f | %s |" % (
            r["size"], r["scalar_type"], r["representation"], ran, r["read_ms"], r["first_frame_ms"],
            r["frame_median_ms"], r["frame_max_ms"], r["read_peak_bytes"] / 1e6,
            r["first_frame_peak_bytes"] / 1e6, r["orbit_peak_bytes"] / 1e6, r["process_peak_bytes"] / 1e6,
            r["peak_ratio"], " ".join("%.0f" % (b / 1e6) for b in r["orbit_rss_bytes"]), r["first_frame_ns_per_voxel"],
            "%.4f" % r["rmse_vs_volume"] if "rmse_vs_volume" in r else ("drew nothing" if r["blank"] else "")))


if __name__ == "__main__":
    main()
