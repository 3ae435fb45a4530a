"""pvbatch test of the "Hybrid Octree OME-Zarr Reader" and the "Hybrid Octree
Volume" representation drawing from the store.

    pvbatch test_zarr_reader.py --plugin <HybridOctree.so> --cli <hybrid-octree> --workdir <dir>

The CLI writes the 64^3 Shepp-Logan phantom (f32) as an OME-Zarr store and as
a .vti. File > Open's factory picks the reader for the .ome.zarr folder; at
Maximum Megabytes 0.2 it reads level 1 (33^3, spacing 2). Shown as "Hybrid
Octree Volume" at a 0.25 MB budget (several strides), the representation
draws the full resolution from disk; the .vti read into memory, shown the
same way with the same colour map, opacity and camera, draws the same bricks
and the same picture: RMSE at most 1e-3 (measured 0: identical). With
Asynchronous Loading on, the first frame draws bricks still loading by
stand-ins (Bricks Loading above 0), later frames refine it until none is
loading, and that picture is the store's synchronous one (RMSE at most 1e-3),
the store's MB read reported. A missing
folder and a damaged zarr.json are refused with the reason in VTK's output,
an empty output, no crash.
"""
import argparse
import os
import shutil
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from paraview.simple import *  # noqa: E402,F401,F403
from pvtest import Checks, generate_phantom, report, rmse, window_rgb  # noqa: E402
from representation_scene import look_at, make_view, show_volume  # noqa: E402

parser = argparse.ArgumentParser()
parser.add_argument("--plugin", required=True)
parser.add_argument("--cli", required=True)
parser.add_argument("--workdir", required=True)
args = parser.parse_args()
os.makedirs(args.workdir, exist_ok=True)
t = Checks("HybridOctree OME-Zarr reader test")
t.log_vtk_output(os.path.join(args.workdir, "vtk_output.txt"))
LoadPlugin(args.plugin, remote=False, ns=globals())
HYBRID = "Hybrid Octree Volume"

store = os.path.join(args.workdir, "phantom64.ome.zarr")
shutil.rmtree(store, ignore_errors=True)
subprocess.run([args.cli, "convert", "--dataset", "shepp-logan", "--size", "64", "--output", store],
               check=True, capture_output=True)
vti = generate_phantom(args.cli, args.workdir, 64)

# The reader factory picks the reader for the folder.
reader = OpenDataFile(store)
t.check(reader is not None and reader.GetXMLName() == "HybridOctreeZarrReader",
        "File > Open picks the Hybrid Octree OME-Zarr Reader for a .ome.zarr folder")
if reader is None:
    reader = HybridOctreeOMEZarrReader(FileName=store)
reader.MaximumMegabytes = 0.2
reader.UpdatePipeline()
info = reader.GetDataInformation()
extent = info.GetExtent()
report("light image extent %s, bounds %s" % (list(extent), list(info.GetBounds())))
t.check(list(extent) == [0, 32, 0, 32, 0, 32], "level 1 (33^3) read at 0.2 MB")

memory = XMLImageDataReader(FileName=[vti])
memory.UpdatePipeline()
array = memory.PointData.keys()[0]
value_range = memory.PointData[array].GetRange()
bounds = memory.GetDataInformation().GetBounds()
light_array = reader.PointData.keys()[0]


def draw(source, name, colour_array, asynchronous=False):
    view = make_view()
    display = show_volume(source, view, colour_array, HYBRID, value_range)
    display.TextureBudgetMB = 0.25
    display.ViewSelection = "Screen Space"
    display.AsynchronousLoading = int(asynchronous)
    # ParaView's default unit distance is the input's cell size: the light
    # image's is the coarse level's, so both are given the same.
    display.ScalarOpacityUnitDistance = 1.0
    look_at(view, bounds)
    loading = []
    if asynchronous:
        # Render again while bricks arrive (what the GUI does by itself).
        for _ in range(1000):
            display.SMProxy.UpdatePropertyInformation()
            loading.append(display.GetPropertyValue("LastBricksLoading"))
            if loading[-1] == 0:
                break
            time.sleep(0.005)
            Render(view)
        report("%s: bricks loading per frame %s, store MB read %.4f"
               % (name, loading, display.GetPropertyValue("LastStoreMBRead")))
    rgb = window_rgb(view, os.path.join(args.workdir, name + ".png"))
    display.SMProxy.UpdatePropertyInformation()
    return (rgb, display.GetPropertyValue("LastBricks"), display.GetPropertyValue("LastTextureMB"), loading,
            display.GetPropertyValue("LastStoreMBRead"))


disk, disk_bricks, disk_mb, _, _ = draw(reader, "store", light_array)
core, core_bricks, core_mb, _, _ = draw(memory, "memory", array)
loaded, loaded_bricks, _, loading, loaded_mb = draw(reader, "store-async", light_array, asynchronous=True)
difference = rmse(disk, core)
signal = float(abs(core - core[0]).mean())
report("store: %d bricks, %.4f MB; memory: %d bricks, %.4f MB; RMSE %.3g (bound 1e-3), signal %.4f"
       % (disk_bricks, disk_mb, core_bricks, core_mb, difference, signal))
t.check(disk_bricks == core_bricks and disk_bricks > 1, "the same bricks from the store as in memory")
# Resident bytes, not the frame's: the first render (ParaView's camera reset
# to the representation's data bounds, the light image's) leaves textures
# of another view resident, so they are only bounded by the budget.
t.check(max(disk_mb, core_mb) <= 0.25 + 1e-9 and core_mb < 1.0, "textures within the budget, under the full volume")
t.check(signal > 0.01, "the picture shows the phantom")
t.check(difference <= 1e-3, "the picture from the store is the picture in memory")
t.check(len(loading) > 1 and loading[0] > 0 and loading[-1] == 0,
        "asynchronous: the first frame drew stand-ins, later frames loaded every brick: %s" % loading)
t.check(loaded_bricks == disk_bricks and loaded_mb > 0, "asynchronous: the same bricks, the store's bytes read")
t.check(rmse(loaded, disk) <= 1e-3, "asynchronous: refined to the synchronous picture (RMSE %.3g)" % rmse(loaded, disk))
t.check("error" not in t.logged().lower(), "no error while drawing:\n" + t.logged()[-2000:])

# Bad stores: a missing folder, a damaged zarr.json.
missing = HybridOctreeOMEZarrReader(FileName=os.path.join(args.workdir, "no-such.ome.zarr"))
missing.UpdatePipeline()
t.check(missing.GetDataInformation().GetNumberOfPoints() == 0, "a missing folder gives no data")
t.check("not a folder" in t.logged(), "a missing folder is named:\n" + t.logged()[-1000:])
damaged = os.path.join(args.workdir, "damaged.ome.zarr")
shutil.rmtree(damaged, ignore_errors=True)
shutil.copytree(store, damaged)
with open(os.path.join(damaged, "zarr.json"), "w") as f:
    f.write('{ "zarr_format": 3, ')
before = len(t.logged())
broken = HybridOctreeOMEZarrReader(FileName=damaged)
broken.UpdatePipeline()
t.check(broken.GetDataInformation().GetNumberOfPoints() == 0, "a damaged zarr.json gives no data")
t.check("damaged.ome.zarr" in t.logged()[before:], "the damaged store is named:\n" + t.logged()[before:])
t.finish()
