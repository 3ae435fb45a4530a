"""The representation scene drawn by `mpiexec -n N pvbatch mpi_scene.py`.

    mpiexec -n N pvbatch mpi_scene.py --plugin <HybridOctree.so> --data <volume.vti> --image <out.png> --json <out.json>

ParaView's reader reads the volume in N pieces (one per rank), each rank's
"Hybrid Octree Volume" representation builds the octree of its own piece and
draws it, and ParaView composites the ranks' images in visibility order.
Writes the picture and, as JSON, the number of ranks and rank 0's
statistics (run by test_mpi.py).
"""
import argparse
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from paraview import servermanager  # noqa: E402
from paraview.simple import *  # noqa: E402,F401,F403
from representation_scene import SIZE, look_at, make_view, show_volume  # noqa: E402

parser = argparse.ArgumentParser()
parser.add_argument("--plugin", required=True)
parser.add_argument("--data", required=True)
parser.add_argument("--image", required=True)
parser.add_argument("--json", required=True)
parser.add_argument("--surface-opacity", type=float, default=0.5, help="0: no isosurface")
args = parser.parse_args()

LoadPlugin(args.plugin, remote=False, ns=globals())
reader = XMLImageDataReader(FileName=[args.data])
reader.UpdatePipeline()
array = reader.PointData.keys()[0]
view = make_view()
display = show_volume(reader, view, array, "Hybrid Octree Volume", reader.PointData[array].GetRange())
display.ShowIsosurface = 1 if args.surface_opacity > 0 else 0
lo, hi = reader.PointData[array].GetRange()
display.OctreeIsovalue = lo + 0.5 * (hi - lo)
display.IsosurfaceOpacity = max(args.surface_opacity, 0.0)
look_at(view, reader.GetDataInformation().GetBounds())
SaveScreenshot(args.image, view, ImageResolution=list(SIZE))
display.SMProxy.UpdatePropertyInformation()
result = {
    "ranks": servermanager.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions(),
    "points": reader.GetDataInformation().GetNumberOfPoints(),
}
for name in ("LastBricks", "LastTextureMB", "LastPlan", "LastEstimatedError"):
    result[name] = display.GetPropertyValue(name)
with open(args.json, "w") as f:
    json.dump(result, f)
