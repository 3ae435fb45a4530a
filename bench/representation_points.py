"""What the Hybrid Points of the "Hybrid Octree Volume" representation buy at
small texture budgets, in one pvbatch process.

    PYTHONPATH=build/lib/python3.11/site-packages scripts/with-xvfb.sh \
        pvbatch bench/representation_points.py \
        --plugin build/lib/paraview-5.11/plugins/HybridOctree/HybridOctree.so \
        --cli build/cargo/release/hybrid-octree \
        [--dataset shepp-logan] [--size 64] [--budgets 0.1,0.05,0.02] \
        [--factors 2,4] [--thresholds 0.05,0.1,0.2,0.4] [--view-selection Data]
        [--workdir DIR] [--json]

Scene: the one of tests/paraview/test_representation.py. A --size^3 f32
volume of the CLI's built-in --dataset (`hybrid-octree generate`; vessels is
the synthetic angiogram) read by XMLImageDataReader, drawn in a 320x320
render view by the "Hybrid Octree Volume" representation with the tests'
colour map (blue, grey, red over the data range) and opacity function (0 up
to 10 % of the range, 0.02 at 30 %, 0.25 at the top), from the tests' fixed
oblique camera (tests/paraview/representation_scene.py).

The representation's View Selection is --view-selection ("Data" by
default: the points' trade is measured against the data-space selection;
with "Both", 3 of the 24 cells of the default sweep come out at most 0.6 %
above the picture without points, at the 0.1 and 0.02 MB budgets).

Metric: RMSE of RGB in [0, 1] (pvtest.rmse) of SaveScreenshot pictures
against the reference, the same representation at TextureBudgetMB 64 without
points. For every --budgets MB: the picture without points (HybridPoints 0),
then for every --factors x --thresholds the picture with points
(HybridPoints 1, PointFactor, PointThreshold, PointFootprint Square); after
each render the representation's LastPoints and LastTextureMB are read back.

Printed: one row per (budget, factor, threshold): points drawn, texture MB
with points, RMSE without and with points, and their ratio (with / without;
below 1: the points help); then "N of M cells at or below the picture
without points" (and how many of them draw points at all), the worst ratio
and the run time. --json prints one JSON object per row instead of the table.
--check (CTest HybridOctree.Bench.representation_points) fails the run unless
every cell is at or below the picture without points (the goal "points never
make the picture worse"), some cell draws points, and every picture keeps its
textures within the budget.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tests", "paraview"))

from paraview.simple import LoadPlugin, SaveScreenshot, XMLImageDataReader  # noqa: E402
from pvtest import Checks, generate_phantom, read_png_rgb, report, rmse  # noqa: E402
from representation_scene import SIZE, look_at, make_view, show_volume  # noqa: E402


def floats(text):
    return [float(v) for v in text.split(",")]


parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
parser.add_argument("--plugin", required=True, help="HybridOctree.so")
parser.add_argument("--cli", required=True, help="the hybrid-octree CLI")
parser.add_argument("--dataset", default="shepp-logan", help="a built-in dataset of the CLI (shepp-logan, vessels, ...)")
parser.add_argument("--size", type=int, default=64, help="samples per axis")
parser.add_argument("--budgets", type=floats, default=[0.1, 0.05, 0.02], help="texture budgets, MB")
parser.add_argument("--factors", type=lambda s: [int(v) for v in s.split(",")], default=[2, 4])
parser.add_argument("--thresholds", type=floats, default=[0.05, 0.1, 0.2, 0.4])
parser.add_argument("--view-selection", default="Data", choices=["Data", "Screen Space", "Visibility", "Both"],
                    help="the representation's View Selection (default Data)")
parser.add_argument("--workdir", help="where the volume and the pictures go (default: a temporary folder)")
parser.add_argument("--json", action="store_true", help="one JSON object per row instead of the table")
parser.add_argument("--check", action="store_true", help="fail unless points never make a picture worse")
args = parser.parse_args()
workdir = args.workdir or tempfile.mkdtemp(prefix="representation-points-")
os.makedirs(workdir, exist_ok=True)
started = time.perf_counter()


def generate(dataset, size):
    """The CLI's size^3 f32 `dataset` as a .vti in workdir (pvtest's
    generate_phantom for any built-in dataset)."""
    if dataset == "shepp-logan":
        return generate_phantom(args.cli, workdir, size)
    path = os.path.join(workdir, "%s%d.vti" % (dataset, size))
    subprocess.run([args.cli, "generate", "--dataset", dataset, "--size", str(size), "--output", path],
                   check=True, capture_output=True)
    return path


LoadPlugin(args.plugin, remote=False, ns=globals())
reader = XMLImageDataReader(FileName=[generate(args.dataset, args.size)])
reader.UpdatePipeline()
array = reader.PointData.keys()[0]
view = make_view()
display = show_volume(reader, view, array, "Hybrid Octree Volume", reader.PointData[array].GetRange())
look_at(view, reader.GetDataInformation().GetBounds())


def picture(name):
    """Renders; returns the picture and (LastPoints, LastTextureMB)."""
    path = os.path.join(workdir, name + ".png")
    SaveScreenshot(path, view, ImageResolution=list(SIZE))
    display.SMProxy.UpdatePropertyInformation()
    return read_png_rgb(path), (display.GetPropertyValue("LastPoints"), display.GetPropertyValue("LastTextureMB"))


display.ViewSelection = args.view_selection
display.HybridPoints = 0
display.TextureBudgetMB = 64.0
reference, _ = picture("reference-64MB")
rows = []
for budget in args.budgets:
    display.HybridPoints = 0
    display.TextureBudgetMB = budget
    without, _ = picture("%gMB" % budget)
    rmse_without = rmse(without, reference)
    display.HybridPoints = 1
    display.PointFootprint = "Square"
    for factor in args.factors:
        for threshold in args.thresholds:
            display.PointFactor = factor
            display.PointThreshold = threshold
            image, (points, texture_mb) = picture("%gMB-f%d-t%g" % (budget, factor, threshold))
            rmse_with = rmse(image, reference)
            rows.append({"dataset": args.dataset, "size": args.size, "budget_mb": budget, "factor": factor,
                         "threshold": threshold, "points": points, "texture_mb": texture_mb,
                         "rmse_without": rmse_without, "rmse_with": rmse_with,
                         "ratio": rmse_with / rmse_without if rmse_without > 0 else float("inf")})

if args.json:
    for row in rows:
        report(json.dumps(row))
else:
    report("%s %d^3, %dx%d, reference: 64 MB without points" % (args.dataset, args.size, SIZE[0], SIZE[1]))
    report("| budget MB | factor | threshold | points | texture MB | RMSE without | RMSE with | ratio |")
    report("|---|---|---|---|---|---|---|---|")
    for r in rows:
        report("| %g | %d | %g | %d | %.4f | %.4f | %.4f | %.3f |" % (
            r["budget_mb"], r["factor"], r["threshold"], r["points"], r["texture_mb"],
            r["rmse_without"], r["rmse_with"], r["ratio"]))
    better = sum(r["rmse_with"] <= r["rmse_without"] for r in rows)
    worst = max(rows, key=lambda r: r["ratio"])
    drawn = sum(r["points"] > 0 for r in rows)
    report("%d of %d cells at or below the picture without points (%d draw points); worst ratio %.3f "
           "(%g MB, factor %d, threshold %g); %.1f s" % (better, len(rows), drawn, worst["ratio"], worst["budget_mb"],
                                                        worst["factor"], worst["threshold"], time.perf_counter() - started))
if args.check:
    t = Checks("representation_points")
    for r in rows:
        cell = "%g MB, factor %d, threshold %g" % (r["budget_mb"], r["factor"], r["threshold"])
        t.check(r["rmse_with"] <= r["rmse_without"],
                "%s: with points %.5f <= without %.5f" % (cell, r["rmse_with"], r["rmse_without"]))
        t.check(0.0 < r["texture_mb"] <= r["budget_mb"], "%s: texture %.4f MB within the budget" % (cell, r["texture_mb"]))
    t.check(any(r["points"] > 0 for r in rows), "some cell draws points")
    t.finish()
# No sys.exit(): pvbatch 5.11 can crash in its teardown after one (pvtest.Checks.finish).
