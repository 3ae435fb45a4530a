"""A volume on disk in ParaView: OME-Zarr stores written by `hybrid-octree
convert` straight from the generator, drawn by *Hybrid Octree Volume* from
disk with and without Asynchronous Loading, and by ParaView's *Volume* on
the store's full resolution read whole.

    PYTHONPATH=build/lib/python3.11/site-packages scripts/with-xvfb.sh pvbatch bench/out_of_core.py \\
        --plugin build/lib/paraview-5.11/plugins/HybridOctree/HybridOctree.so \\
        --cli build/cargo/release/hybrid-octree \\
        [--sizes 1024,2048] [--dataset vessels] [--budget-mb 64] [--loading-mb 256] \\
        [--width 512 --height 512] [--workdir DIR] [--keep] [--no-volume] [--json]

Per size (N: a cube; XxYxZ: a box; u8):

- convert: `hybrid-octree convert --dataset ... --output X.ome.zarr` (the
  volume never whole in memory), its wall time, MB/s of raw samples and
  the child's peak RSS (`ru_maxrss`); an existing store is reused with
  --keep;
- one pvbatch process per case (this script with --case):
  - `async`: the *Hybrid Octree OME-Zarr Reader* (light level of 64 MB),
    shown as *Hybrid Octree Volume* with Asynchronous Loading: open (the
    reader's update), the first picture (shown, coloured, the camera set,
    drawn: from the reader's creation), the bricks still loading in it,
    then still frames until none is loading: their count and the time to
    the refined picture (from the reader's creation);
  - `sync`: the same without Asynchronous Loading: the first picture is
    the whole one;
  - `volume`: ParaView's *Volume* on the full resolution read whole (the
    reader's Maximum Megabytes above the volume), or its failure;
  each with its peak RSS (`ru_maxrss`) and its last picture;
- RMSE of the async case's refined picture against the sync case's
  (they should be equal), and of the first async picture against it.

Every case draws with the same scalar opacity unit distance (--unit-distance,
the full resolution's spacing): ParaView's default is the input's cell
size, which for the reader's light output is the coarse level's.
"""
import argparse
import json
import os
import resource
import shutil
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tests", "paraview"))

HYBRID = "Hybrid Octree Volume"
VOLUME = "Volume"


def parse():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--plugin", required=True)
    p.add_argument("--cli", required=True)
    p.add_argument("--sizes", default="1024")
    p.add_argument("--dataset", default="vessels")
    p.add_argument("--budget-mb", type=float, default=64.0)
    p.add_argument("--loading-mb", type=float, default=256.0)
    p.add_argument("--width", type=int, default=512)
    p.add_argument("--height", type=int, default=512)
    p.add_argument("--max-frames", type=int, default=2000)
    p.add_argument("--unit-distance", type=float, default=1.0,
                   help="the scalar opacity unit distance of every case: the full resolution's spacing (the "
                   "generated datasets': 1); ParaView's default would be the light image's, coarser")
    p.add_argument("--workdir", default=None)
    p.add_argument("--keep", action="store_true", help="reuse stores already written, keep them after")
    p.add_argument("--no-volume", action="store_true", help="leave out ParaView's Volume on the data read whole")
    p.add_argument("--json", action="store_true")
    p.add_argument("--check", action="store_true", help="exit 1 unless every row is complete, the async case "
                   "loaded every brick and refined to the sync picture (RMSE <= 1e-3) (no timing checked)")
    # One case (internal).
    p.add_argument("--case", default=None)
    p.add_argument("--store", default=None)
    p.add_argument("--png", default=None)
    p.add_argument("--first-png", default=None)
    return p.parse_args()


def peak_self():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024


def run_case(args):
    """One case on one store, in this process: prints one JSON line."""
    from paraview.simple import LoadPlugin, Render
    from representation_scene import look_at, make_view, show_volume
    from pvtest import window_rgb

    LoadPlugin(args.plugin, remote=False)
    from paraview.simple import HybridOctreeOMEZarrReader

    out = {"case": args.case}
    start = time.perf_counter()
    reader = HybridOctreeOMEZarrReader(FileName=args.store)
    # The full resolution whole for ParaView's Volume; else a light level.
    reader.MaximumMegabytes = 1e9 if args.case == "volume" else 64.0
    reader.UpdatePipeline()
    out["open_ms"] = (time.perf_counter() - start) * 1e3
    info = reader.GetDataInformation()
    out["light_points"] = info.GetNumberOfPoints()
    array = reader.PointData.keys()[0]
    # The octree's range would be the store's; the light level's is the reader's.
    value_range = reader.PointData[array].GetRange()
    bounds = info.GetBounds()
    view = make_view((args.width, args.height))
    representation = VOLUME if args.case == "volume" else HYBRID
    display = show_volume(reader, view, array, representation, value_range)
    display.ScalarOpacityUnitDistance = args.unit_distance
    if representation == HYBRID:
        display.TextureBudgetMB = args.budget_mb
        display.LoadingMemoryMB = args.loading_mb
        display.AsynchronousLoading = int(args.case == "async")
    look_at(view, bounds)  # renders: the first picture
    view.GetRenderWindow().WaitForCompletion()
    out["first_ms"] = (time.perf_counter() - start) * 1e3
    out["first_peak_bytes"] = peak_self()
    frames = 1
    loading = []
    if representation == HYBRID:
        display.SMProxy.UpdatePropertyInformation()
        loading.append(display.GetPropertyValue("LastBricksLoading"))
        out["bricks"] = display.GetPropertyValue("LastBricks")
        out["draws"] = display.GetPropertyValue("LastBrickDraws")
        if args.case == "async" and args.first_png:
            window_rgb(view, args.first_png)  # as drawn, not drawn again
        while loading[-1] > 0 and frames < args.max_frames:
            time.sleep(0.01)
            Render(view)
            view.GetRenderWindow().WaitForCompletion()
            frames += 1
            display.SMProxy.UpdatePropertyInformation()
            loading.append(display.GetPropertyValue("LastBricksLoading"))
        out["refined_bricks"] = display.GetPropertyValue("LastBricks")
        out["refined_draws"] = display.GetPropertyValue("LastBrickDraws")
        out["store_mb_read"] = display.GetPropertyValue("LastStoreMBRead")
        out["texture_mb"] = display.GetPropertyValue("LastTextureMB")
        out["estimated_error"] = display.GetPropertyValue("LastEstimatedError")
    out["refined_ms"] = (time.perf_counter() - start) * 1e3
    out["frames"] = frames
    out["loading_first"] = loading[0] if loading else 0
    out["loading_last"] = loading[-1] if loading else 0
    out["loading_trace"] = loading[:12] + (["..."] if len(loading) > 12 else [])
    if args.png:
        window_rgb(view, args.png)
    out["peak_bytes"] = peak_self()
    print("CASE " + json.dumps(out), flush=True)


def spawn(args, case, store, png, first_png):
    command = [sys.executable if os.path.basename(sys.executable).startswith("pv") else "pvbatch",
               os.path.abspath(__file__), "--plugin", args.plugin, "--cli", args.cli, "--case", case,
               "--store", store, "--png", png, "--first-png", first_png, "--budget-mb", str(args.budget_mb),
               "--loading-mb", str(args.loading_mb), "--width", str(args.width), "--height", str(args.height),
               "--max-frames", str(args.max_frames), "--unit-distance", str(args.unit_distance)]
    done = subprocess.run(command, capture_output=True, text=True)
    for line in done.stdout.splitlines():
        if line.startswith("CASE "):
            return json.loads(line[len("CASE "):])
    errors = [x for x in (done.stderr + done.stdout).splitlines() if x.strip()]
    return {"case": case, "failed": "exit status %d: %s" % (done.returncode, errors[-1][:200] if errors else "")}


def convert(args, size, store):
    """Writes the store; its row."""
    if args.keep and os.path.isdir(store):
        return {"reused": True}
    shutil.rmtree(store, ignore_errors=True)
    t = time.perf_counter()
    with tempfile.TemporaryFile("w+") as errors:
        child = subprocess.Popen([args.cli, "convert", "--dataset", args.dataset, "--size", size, "--type", "u8",
                                  "--output", store, "--json"], stdout=subprocess.DEVNULL, stderr=errors, text=True)
        # This child's own rusage: RUSAGE_CHILDREN's ru_maxrss is the largest child so far (an
        # earlier size's pvbatch case).
        _, status, usage = os.wait4(child.pid, 0)
        child.returncode = os.waitstatus_to_exitcode(status)
        wall = time.perf_counter() - t
        errors.seek(0)
        stderr = errors.read()
    if child.returncode != 0:
        return {"failed": stderr.strip().splitlines()[-1:] or ["exit %d" % child.returncode]}
    disk = sum(os.path.getsize(os.path.join(d, f)) for d, _, fs in os.walk(store) for f in fs)
    return {"wall_s": wall, "peak_bytes": usage.ru_maxrss * 1024, "disk_bytes": disk}


def check(rows):
    """What --check finds wrong in `rows`."""
    problems = []
    for r in rows:
        size = r["size"]
        if "wall_s" not in r["convert"] and not r["convert"].get("reused"):
            problems.append("%s: convert failed: %s" % (size, r["convert"]))
        for case in ("sync", "async"):
            x = r.get(case, {})
            if "failed" in x or x.get("blank", True):
                problems.append("%s %s: %s" % (size, case, x.get("failed", "drew nothing")))
        a = r.get("async", {})
        if a.get("loading_last", 1) != 0 or not a.get("store_mb_read", 0) > 0:
            problems.append("%s async: bricks still loading %s, store MB read %s"
                            % (size, a.get("loading_last"), a.get("store_mb_read")))
        e = r.get("rmse_vs_sync", {}).get("async")
        if e is None or e > 1e-3:
            problems.append("%s async: refined picture RMSE %s against the sync one (bound 1e-3)" % (size, e))
    return problems


def dims_of(size):
    parts = [int(x) for x in size.lower().split("x")]
    return parts * 3 if len(parts) == 1 else parts


def main():
    args = parse()
    if args.case:
        run_case(args)
        return
    from pvtest import read_png_rgb, rmse

    workdir = args.workdir or os.path.join(os.getcwd(), "out-of-core")
    os.makedirs(workdir, exist_ok=True)
    rows = []
    for size in [s for s in args.sizes.split(",") if s]:
        d = dims_of(size)
        volume_bytes = d[0] * d[1] * d[2]
        store = os.path.join(workdir, "%s-%s.ome.zarr" % (args.dataset, size))
        row = {"size": size, "volume_bytes": volume_bytes, "convert": convert(args, size, store)}
        pictures = {}
        for case in ["sync", "async"] + ([] if args.no_volume else ["volume"]):
            png = os.path.join(workdir, "%s-%s-%s.png" % (args.dataset, size, case))
            first_png = os.path.join(workdir, "%s-%s-%s-first.png" % (args.dataset, size, case))
            for f in (png, first_png):
                if os.path.exists(f):
                    os.remove(f)
            result = spawn(args, case, store, png, first_png)
            if "failed" not in result and os.path.exists(png):
                pictures[case] = read_png_rgb(png)
                result["blank"] = bool(pictures[case].std(axis=0).max() < 1e-3)
                if os.path.exists(first_png):
                    pictures[case + "-first"] = read_png_rgb(first_png)
            row[case] = result
        if "sync" in pictures:
            for name in ("async", "async-first", "volume"):
                if name in pictures and pictures[name].shape == pictures["sync"].shape:
                    row.setdefault("rmse_vs_sync", {})[name] = rmse(pictures[name], pictures["sync"])
        rows.append(row)
        if not args.keep:
            shutil.rmtree(store, ignore_errors=True)
    if args.check:
        problems = check(rows)
        for p in problems:
            print("CHECK FAILED: " + p)
        if problems:
            print(json.dumps(rows, indent=1))
            sys.exit(1)
    if args.json:
        print(json.dumps(rows, indent=1))
        return
    print("%s u8, %dx%d, budget %.0f MB, loading memory %.0f MB" % (args.dataset, args.width, args.height,
                                                                  args.budget_mb, args.loading_mb))
    print("| size | convert s | MB/s | convert peak MB | store MB |")
    print("| --- | ---: | ---: | ---: | ---: |")
    for r in rows:
        c = r["convert"]
        if "wall_s" in c:
            print("| %s | %.1f | %.1f | %.0f | %.1f |" % (r["size"], c["wall_s"], r["volume_bytes"] / 1e6 / c["wall_s"],
                                                      c["peak_bytes"] / 1e6, c["disk_bytes"] / 1e6))
        else:
            print("| %s | %s |" % (r["size"], c))
    print()
    print("| size | case | open ms | first picture ms | bricks loading in it | frames | refined ms | store MB read "
          "| peak RSS MB | bricks / draw calls (first, refined) | RMSE vs sync |")
    print("| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- | --- |")
    for r in rows:
        errors = r.get("rmse_vs_sync", {})
        for case in ("sync", "async", "volume"):
            x = r.get(case)
            if x is None:
                continue
            if "failed" in x:
                print("| %s | %s | failed: %s |" % (r["size"], case, x["failed"]))
                continue
            e = ", ".join("%s %.4f" % (k, v) for k, v in errors.items() if k.startswith(case))
            if x.get("blank"):
                e = "drew nothing"
            draws = "%s / %s, %s / %s" % (x["bricks"], x["draws"], x["refined_bricks"], x["refined_draws"]) \
                if "draws" in x else ""
            print("| %s | %s | %.0f | %.0f | %s | %d | %.0f | %s | %.0f | %s | %s |" % (
                r["size"], case, x["open_ms"], x["first_ms"], x.get("loading_first", ""), x["frames"],
                x["refined_ms"], "%.1f" % x["store_mb_read"] if "store_mb_read" in x else "",
                x["peak_bytes"] / 1e6, draws, e))


if __name__ == "__main__":
    main()
