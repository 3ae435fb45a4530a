"""ParaView GUI start-up script for scripts/gui_screenshot.sh: the phantom
with the Hybrid Octree Volume representation, a translucent isosurface and a
region of interest (HO_PLUGIN: the plugin, HO_DATA: the .vti)."""
from paraview.simple import *
import os
LoadPlugin(os.environ["HO_PLUGIN"], remote=False, ns=globals())
reader = XMLImageDataReader(registrationName="phantom.vti", FileName=[os.environ["HO_DATA"]])
reader.UpdatePipeline()
array = reader.PointData.keys()[0]
lo, hi = reader.PointData[array].GetRange()
view = GetActiveViewOrCreate("RenderView")
d = Show(reader, view)
d.SetRepresentationType("Hybrid Octree Volume")
ColorBy(d, ("POINTS", array))
lut = GetColorTransferFunction(array); lut.ApplyPreset("Cool to Warm", True)
pwf = GetOpacityTransferFunction(array)
w = hi - lo
pwf.Points = [lo, 0.0, 0.5, 0.0, lo + 0.1 * w, 0.0, 0.5, 0.0, lo + 0.3 * w, 0.03, 0.5, 0.0, hi, 0.3, 0.5, 0.0]
d.ShowIsosurface = 1
d.OctreeIsovalue = lo + 0.5 * w
d.IsosurfaceOpacity = 0.35
d.IsosurfaceColor = [0.95, 0.8, 0.6]
d.TextureBudgetMB = 16
d.UseRegionOfInterest = 1
d.RegionOfInterestCenter = [64.0, 40.0, 64.0]
d.RegionOfInterestRadius = 24.0
d.SetScalarBarVisibility(view, True)
view.ResetCamera()
cam = view.GetActiveCamera(); cam.Azimuth(35); cam.Elevation(20)
SetActiveSource(reader)
Render(view)
