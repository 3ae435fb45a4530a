"""The README's main job, ParaView side: load the plugin, read a volume, apply
the Hybrid Octree filter, print what it built, render the node boxes of the
cut coloured by level next to a contour of the data, and save a PNG."""
import argparse

from paraview.simple import (ColorBy, Contour, GetActiveViewOrCreate, LoadPlugin, ResetCamera,
                             SaveScreenshot, Show, XMLImageDataReader)

ap = argparse.ArgumentParser()
ap.add_argument("--plugin", required=True)
ap.add_argument("--input", required=True)
ap.add_argument("--output", default="hybrid-octree-demo.png")
ap.add_argument("--tolerance", type=float, default=0.01)
args = ap.parse_args()

LoadPlugin(args.plugin, remote=False, ns=globals())
reader = XMLImageDataReader(FileName=[args.input])
reader.UpdatePipeline()
octree = HybridOctree(Input=reader, ErrorTolerance=args.tolerance)  # noqa: F821 (defined by LoadPlugin)
octree.UpdatePipeline()

fd = octree.GetClientSideObject().GetOutputDataObject(0).GetFieldData()
def value(name):
    return fd.GetArray(name).GetValue(0)
print(f"Hybrid Octree filter: {int(value('node_count'))} nodes, {int(value('levels'))} levels, "
      f"{int(value('cut_count'))} boxes in the cut at tolerance {args.tolerance}, "
      f"{int(value('octree_bytes'))} octree bytes for {int(value('input_bytes'))} input bytes, "
      f"built in {value('build_ms'):.1f} ms")

view = GetActiveViewOrCreate("RenderView")
view.ViewSize = [1024, 768]
boxes = Show(octree, view)
ColorBy(boxes, ("CELLS", "level"))
boxes.RescaleTransferFunctionToDataRange(True, False)
lo, hi = reader.PointData[0].GetRange()
surface = Contour(Input=reader, ContourBy=["POINTS", reader.PointData[0].Name], Isosurfaces=[lo + 0.5 * (hi - lo)])
shown = Show(surface, view)
shown.Opacity = 0.35
view.CameraPosition = [-1.2, -1.6, 1.0]
view.CameraFocalPoint = [0, 0, 0]
view.CameraViewUp = [0, 0, 1]
ResetCamera(view)
SaveScreenshot(args.output, view, ImageResolution=[1024, 768])
print(f"wrote {args.output}")
