"""Each rendering effect in ParaView: the plugin's "Hybrid Octree Volume"
representation at the full budget against ParaView's own "Volume"
representation (GPU ray cast), in one pvbatch process.

    PYTHONPATH=build/lib/python3.11/site-packages scripts/with-xvfb.sh \
        pvbatch bench/effects_vs_paraview.py \
        --plugin build/lib/paraview-5.11/plugins/HybridOctree/HybridOctree.so \
        --cli build/cargo/release/hybrid-octree \
        [--size 128] [--frames 5] [--width 512 --height 512] [--datasets phantom,wavelet] \
        [--effects plain,shade,...] [--workdir DIR] [--json] [--check]

Data: the CLI's Shepp-Logan phantom at --size^3 f32 (`hybrid-octree
generate`, read with XMLImageDataReader: piecewise constant, sharp edges)
and ParaView's Wavelet source over --size^3 samples (RTData: smooth).

Scene (tests/paraview/representation_scene.py): one display whose
representation type is switched between "Volume" and "Hybrid Octree
Volume", ParaView's cool-to-warm colours and a fixed opacity ramp over the
data range, a fixed oblique perspective camera, ParaView's light kit. The
hybrid representation draws at the full budget: Texture Budget the bytes of
every leaf brick at stride 1 with its gradient border (its estimated error
then 0). Each row of EFFECTS sets display
properties over ParaView's defaults (the properties every row touches are
put back before the next row).

Per row and representation: one untimed still frame (octree, uploads,
shaders), then --frames still frames timed (StillRender + glFinish, the
median); the picture of the last. Printed per dataset and effect: the
median ms of each, the ratio Hybrid / Volume, the RMSE (RGB in [0, 1])
between the two pictures, our plan (the passes), texture MB and estimated
error; then the peak RSS of the process. --json prints one JSON object.
--check (the CTest smoke run) fails unless every row is complete, the plan
is the row's volume pass ("volume", "volume-isosurface"), "-shaded" exactly
in the shaded rows, the effects name cropping
exactly in the cropped row, the estimated error is 0 and
the RMSE below --max-rmse.
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

from paraview import servermanager  # noqa: E402
from paraview.simple import (Delete, GetTransferFunction2D, Hide, LoadPlugin, Render,  # noqa: E402
                             Wavelet, XMLImageDataReader)
from pvtest import Checks, generate_phantom, report, rmse, window_rgb  # noqa: E402
from representation_scene import look_at, make_view, show_volume  # noqa: E402

HYBRID = "Hybrid Octree Volume"
VOLUME = "Volume"


# One line per effect: its name and the display properties it sets (a dict,
# or a function of the data's bounds (xmin, xmax, ymin, ...), value range
# (lo, hi) and point array name returning one).
EFFECTS = [
    ("plain", {}),
    ("shade", {"Shade": 1}),
    ("shade-ambient", {"Shade": 1, "Ambient": 0.3, "Diffuse": 0.7}),
    ("shade-diffuse", {"Shade": 1, "Diffuse": 0.5}),
    ("shade-specular", {"Shade": 1, "Specular": 0.5, "SpecularPower": 30.0}),
    ("shade-glossy", {"Shade": 1, "Specular": 1.0, "SpecularPower": 100.0}),
    # Use Cropping: the box [o + min s, o + max s] keeps 20 % to 70 % of each axis of the bounds b.
    ("cropping", lambda b, r, a: {"UseCropping": 1, "CroppingScale": [0.5] * 3,
                               "CroppingOrigin": [0.5 * b[2 * a] + 0.2 * (b[2 * a + 1] - b[2 * a])
                                                  for a in range(3)]}),
    # Isosurface at a quarter and 70 % of the range; the unit distance the
    # sample spacing, as in the rows of docs/BENCHMARKS.md (VTK and the mapper
    # take the opacity table as it is in this mode, whatever the unit distance).
    ("isosurface", lambda b, r, a: {"BlendMode": "Isosurface", "ScalarOpacityUnitDistance": 1.0,
                                 "IsosurfaceValues": [r[0] + 0.25 * (r[1] - r[0]), r[0] + 0.7 * (r[1] - r[0])]}),
    ("shade-isosurface", lambda b, r, a: {"Shade": 1, "BlendMode": "Isosurface", "ScalarOpacityUnitDistance": 1.0,
                                       "IsosurfaceValues": [r[0] + 0.25 * (r[1] - r[0]),
                                                            r[0] + 0.7 * (r[1] - r[0])]}),
    # Use 2D Transfer Function: tests/paraview/test_transfer2d.py's two boxes
    # (soft values at low gradient, bright ones at high gradient).
    ("transfer-2d", lambda b, r, a: {"UseTransfer2D": 1, "UseGradientForTransfer2D": 1,
                                     "TransferFunction2D": two_boxes(a, r)}),
]


def two_boxes(array, value_range):
    """ParaView's TransferFunction2D of `array` with two boxes over value and
    gradient magnitude (its y axis a quarter of the value range)."""
    lo, hi = value_range
    w = hi - lo
    g = 0.25 * w
    tf2d = GetTransferFunction2D(array)
    tf2d.Range = [lo, hi, 0.0, g]
    tf2d.OutputDimensions = [128, 128]
    tf2d.Boxes = [lo + 0.12 * w, 0.0, 0.36 * w, 0.12 * g, 0.95, 0.75, 0.45, 0.08,
                  lo + 0.45 * w, 0.08 * g, 0.55 * w, 0.92 * g, 0.35, 0.6, 1.0, 0.5]
    return tf2d


def printable(properties):
    """`properties` with each proxy (a TransferFunction2D) named by its XML name, for the table and --json."""
    return {k: v.GetXMLName() if isinstance(v, servermanager.Proxy) else v for k, v in properties.items()}


def properties_of(properties, bounds, value_range, array):
    """The display properties of one EFFECTS entry for the data's bounds, value range and array."""
    return properties(bounds, value_range, array) if callable(properties) else properties

parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
parser.add_argument("--plugin", required=True, help="HybridOctree.so")
parser.add_argument("--cli", required=True, help="the hybrid-octree CLI")
parser.add_argument("--size", type=int, default=128, help="samples per axis of both datasets")
parser.add_argument("--datasets", default="phantom,wavelet", help="phantom, wavelet or both")
parser.add_argument("--effects", default="", help="effect names, comma-separated (default: all)")
parser.add_argument("--frames", type=int, default=5, help="timed still frames per row and representation")
parser.add_argument("--width", type=int, default=512)
parser.add_argument("--height", type=int, default=512)
parser.add_argument("--workdir", help="the phantom and the pictures (default: a temporary folder)")
parser.add_argument("--json", action="store_true", help="one JSON object instead of the table")
parser.add_argument("--check", action="store_true", help="fail unless every row is complete and close")
parser.add_argument("--max-rmse", type=float, default=0.05, help="--check's RMSE bound, Hybrid vs Volume")
args = parser.parse_args()
names = [n for n in args.effects.split(",") if n]
unknown = [n for n in names if n not in [e[0] for e in EFFECTS]]
if unknown:
    parser.error("unknown effect %s: choose from %s" % (unknown, ", ".join(e[0] for e in EFFECTS)))
effects = [e for e in EFFECTS if not names or e[0] in names]
if args.frames < 1 or args.size < 8:
    parser.error("--frames must be at least 1 and --size at least 8")
workdir = args.workdir or tempfile.mkdtemp(prefix="effects-vs-paraview-")
os.makedirs(workdir, exist_ok=True)
started = time.perf_counter()
LoadPlugin(args.plugin, remote=False, ns=globals())


def timed(view):
    """One still frame of `view` to glFinish, ms."""
    t = time.perf_counter()
    view.SMProxy.StillRender()
    view.GetRenderWindow().WaitForCompletion()
    return (time.perf_counter() - t) * 1e3


def info(display, name):
    display.SMProxy.UpdatePropertyInformation()
    return display.GetPropertyValue(name)


def full_budget_mb(extent, leaf):
    """The texture MB of every leaf brick at stride 1 with its gradient
    border: per axis ceil(cells / leaf) bricks of leaf + 3 texels, 4 bytes a
    texel (as `hybrid-octree bench effects`; the budget slider's end, the
    whole input at stride 1, leaves the border out)."""
    texels = 1
    for a in range(3):
        cells = max(extent[2 * a + 1] - extent[2 * a], 1)
        texels *= -(-cells // leaf) * (leaf + 3)
    return 4.0 * texels / 1e6


def source_of(dataset):
    if dataset == "phantom":
        return XMLImageDataReader(FileName=[generate_phantom(args.cli, workdir, args.size)])
    half = args.size // 2
    return Wavelet(WholeExtent=[-half, args.size - 1 - half] * 3)


def measure(view, display, representation, name):
    """Warm-up, timed frames and the last picture of `representation`."""
    display.SetRepresentationType(representation)
    timed(view)
    frames = [timed(view) for _ in range(args.frames)]
    picture = window_rgb(view, os.path.join(workdir, name + ".png"))
    return statistics.median(frames), picture


def snapshot(value):
    """A property's value as plain Python: GetPropertyValue gives vector and
    enumeration properties as live objects, which later changes would alter."""
    if isinstance(value, servermanager.EnumerationProperty):
        return value.GetData()
    if isinstance(value, servermanager.VectorProperty):
        return list(value)
    return value


def run_dataset(dataset):
    source = source_of(dataset)
    source.UpdatePipeline()
    array = source.PointData.keys()[0]
    value_range = source.PointData[array].GetRange()
    bounds = source.GetDataInformation().GetBounds()
    view = make_view()
    view.ViewSize = [args.width, args.height]
    display = show_volume(source, view, array, HYBRID, value_range)
    look_at(view, bounds)
    display.TextureBudgetMB = full_budget_mb(source.GetDataInformation().GetExtent(),
                                             display.SMProxy.GetProperty("OctreeLeafSize").GetElement(0))
    touched = sorted({k for _, p in EFFECTS for k in properties_of(p, bounds, value_range, array)})
    defaults = {k: snapshot(display.GetPropertyValue(k)) for k in touched}
    defaults_seen.update(defaults)
    rows = []
    for name, properties in effects:
        for k, v in defaults.items():
            setattr(display, k, v)
        for k, v in properties_of(properties, bounds, value_range, array).items():
            setattr(display, k, v)
        stem = "%s-%s" % (dataset, name)
        volume_ms, volume_picture = measure(view, display, VOLUME, stem + "-volume")
        hybrid_ms, hybrid_picture = measure(view, display, HYBRID, stem + "-hybrid")
        rows.append({"dataset": dataset, "effect": name,
                     "properties": printable(properties_of(properties, bounds, value_range, array)),
                     "volume_ms": volume_ms, "hybrid_ms": hybrid_ms,
                     "ratio": hybrid_ms / volume_ms, "rmse": rmse(hybrid_picture, volume_picture),
                     "plan": info(display, "LastPlan"), "effects": info(display, "LastEffects"), "texture_mb": info(display, "LastTextureMB"),
                     "estimated_error": info(display, "LastEstimatedError")})
    Hide(source, view)
    Delete(display)
    Delete(source)
    Delete(view)
    return rows


rows = []
defaults_seen = {}
for dataset in args.datasets.split(","):
    rows.extend(run_dataset(dataset))
peak_mb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0

if args.json:
    report(json.dumps({"size": args.size, "width": args.width, "height": args.height, "frames": args.frames,
                       "rows": rows, "peak_rss_mb": peak_mb}))
else:
    report("%d^3, %dx%d, median of %d still frames after a warm-up (StillRender + glFinish), ms; "
           "Hybrid at the full budget" % (args.size, args.width, args.height, args.frames))
    report("| dataset | effect | Volume ms | Hybrid ms | Hybrid / Volume | RMSE | plan | texture MB | est. error "
           "| properties |")
    report("|---|---|---:|---:|---:|---:|---|---:|---:|---|")
    for r in rows:
        report("| %s | %s | %.1f | %.1f | %.2f | %.4f | %s | %.1f | %.4f | %s |" % (
            r["dataset"], r["effect"], r["volume_ms"], r["hybrid_ms"], r["ratio"], r["rmse"], r["plan"],
            r["texture_mb"], r["estimated_error"],
            ", ".join("%s %s" % kv for kv in sorted(r["properties"].items())) or "-"))
    report("ParaView's defaults: " + ", ".join("%s %s" % kv for kv in sorted(printable(defaults_seen).items())))
    report("peak RSS %.0f MB; %.1f s" % (peak_mb, time.perf_counter() - started))
if args.check:
    t = Checks("effects_vs_paraview")
    t.check(len(rows) == len(effects) * len(args.datasets.split(",")), "%d rows" % len(rows))
    for r in rows:
        what = "%s %s" % (r["dataset"], r["effect"])
        t.check(r["volume_ms"] > 0.0 and r["hybrid_ms"] > 0.0, what + ": times")
        shaded = bool(r["properties"].get("Shade"))
        volume_pass = "volume-isosurface" if r["properties"].get("BlendMode") == "Isosurface" else "volume"
        expected = volume_pass + ("-shaded" if shaded else "")
        t.check(r["plan"] == expected, what + ": plan %r, not %r" % (r["plan"], expected))
        two_d = bool(r["properties"].get("UseTransfer2D"))
        t.check(("transfer-2d" in r["effects"].split(",")) == two_d, what + ": effects %r" % r["effects"])
        cropped = bool(r["properties"].get("UseCropping"))
        t.check(("cropping" in r["effects"].split(",")) == cropped, what + ": effects %r" % r["effects"])
        t.check(r["estimated_error"] == 0.0, what + ": full budget, estimated error %g" % r["estimated_error"])
        t.check(r["rmse"] <= args.max_rmse, what + ": RMSE %.4f above %g" % (r["rmse"], args.max_rmse))
    t.finish()
# No sys.exit(): pvbatch 5.11 can crash in its teardown after one (pvtest.Checks.finish).
