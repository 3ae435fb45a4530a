"""The README's main job, ParaView side: load the plugin, read a volume, apply
the Hybrid Octree filter, print what it built, render the node boxes of the
cut coloured by level together with the filter's own isosurface (port 1, the
DiscMC surface with merged facets), and save a PNG; then draw the volume with
the plugin's "Hybrid Octree Volume" representation (a translucent isosurface
inside) and print what its last frame drew."""
import argparse

from paraview.simple import (ColorBy, CreateView, GetActiveViewOrCreate, GetOpacityTransferFunction,
                             LoadPlugin, OutputPort, Render, ResetCamera, SaveScreenshot, Show,
                             XMLImageDataReader)

ap = argparse.ArgumentParser()
ap.add_argument("--plugin", required=True)
ap.add_argument("--input", required=True)
ap.add_argument("--output", default="hybrid-octree-demo.png")
ap.add_argument("--representation-output", default="hybrid-octree-representation.png")
ap.add_argument("--tolerance", type=float, default=0.01)
ap.add_argument("--isovalue", type=float, default=0.5)
args = ap.parse_args()

LoadPlugin(args.plugin, remote=False, ns=globals())
reader = XMLImageDataReader(FileName=[args.input])
reader.UpdatePipeline()
octree = HybridOctree(Input=reader, ErrorTolerance=args.tolerance,  # noqa: F821 (defined by LoadPlugin)
                      Isovalue=args.isovalue, SurfaceMode=0, MeasureSurfaceDistance=1)
octree.UpdatePipeline()

def field(port, name):
    """The one value of field-data array `name` on output `port` of the filter."""
    return octree.GetClientSideObject().GetOutputDataObject(port).GetFieldData().GetArray(name).GetValue(0)


def value(name):
    return field(0, name)


print(f"Hybrid Octree filter: {int(value('node_count'))} nodes, {int(value('levels'))} levels, "
      f"{int(value('cut_count'))} boxes in the cut at tolerance {args.tolerance}, "
      f"{int(value('octree_bytes'))} octree bytes for {int(value('input_bytes'))} input bytes, "
      f"built in {value('build_ms'):.1f} ms")


def surface(name):
    return field(1, name)


print(f"Surface at {args.isovalue}: {int(surface('faces'))} merged DiscMC faces "
      f"({int(surface('triangles'))} triangles, {int(surface('uncompressed_triangles'))} before face compression), "
      f"{int(surface('boundary_edges'))} boundary edges, "
      f"{surface('extract_ms') + surface('compress_ms'):.1f} ms; "
      f"{surface('distance_mean'):.3f} voxel mean / {surface('distance_max'):.3f} max from the interpolated surface")

view = GetActiveViewOrCreate("RenderView")
view.ViewSize = [1024, 768]
boxes = Show(octree, view)
ColorBy(boxes, ("CELLS", "level"))
boxes.RescaleTransferFunctionToDataRange(True, False)
shown = Show(OutputPort(octree, 1), view)
shown.Opacity = 0.5
view.CameraPosition = [-1.2, -1.6, 1.0]
view.CameraFocalPoint = [0, 0, 0]
view.CameraViewUp = [0, 0, 1]
ResetCamera(view)
SaveScreenshot(args.output, view, ImageResolution=[1024, 768])
print(f"wrote {args.output}")

# The same volume with the "Hybrid Octree Volume" representation.
volume_view = CreateView("RenderView")
volume_view.ViewSize = [1024, 768]
volume = Show(reader, volume_view)
volume.SetRepresentationType("Hybrid Octree Volume")
array = reader.PointData.keys()[0]
ColorBy(volume, ("POINTS", array))
lo, hi = reader.PointData[array].GetRange()
GetOpacityTransferFunction(array).Points = [lo, 0.0, 0.5, 0.0, lo + 0.1 * (hi - lo), 0.0, 0.5, 0.0,
                                            lo + 0.3 * (hi - lo), 0.02, 0.5, 0.0, hi, 0.25, 0.5, 0.0]
volume.TextureBudgetMB = 16
volume.ShowIsosurface = 1
volume.OctreeIsovalue = args.isovalue
volume.IsosurfaceOpacity = 0.4
Render(volume_view)
volume_view.CameraPosition = [-1.2, -1.6, 1.0]
volume_view.CameraFocalPoint = [0, 0, 0]
volume_view.CameraViewUp = [0, 0, 1]
ResetCamera(volume_view)
SaveScreenshot(args.representation_output, volume_view, ImageResolution=[1024, 768])
volume.SMProxy.UpdatePropertyInformation()
stat = volume.GetPropertyValue
print(f"Hybrid Octree Volume representation at 16 MB: {stat('LastBricks')} bricks, "
      f"{stat('LastTextureMB'):.2f} texture MB, plan '{stat('LastPlan')}', "
      f"estimated error {stat('LastEstimatedError'):.4f}, {stat('LastFrameMilliseconds'):.0f} ms")
print(f"wrote {args.representation_output}")
