"""The README's main job, VTK side: the volume drawn by
vtkHybridOctreeVolumeMapper (OpenGL) with a translucent isosurface, the same
view as `hybrid-octree render` (azimuth 30, elevation 20), saved as a PNG;
prints the mapper's statistics of the frame and its RMSE against the CLI's
full-resolution reference picture when one is given."""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "bench"))
from render_vs_fixed_point import BACKGROUND, look_around, png_rgb, volume_property  # noqa: E402

from hybrid_octree import vtkHybridOctreeVolumeMapper  # noqa: E402
from vtkmodules.vtkIOImage import vtkPNGWriter  # noqa: E402
from vtkmodules.vtkIOXML import vtkXMLImageDataReader  # noqa: E402
from vtkmodules.vtkRenderingCore import vtkRenderer, vtkRenderWindow, vtkVolume, vtkWindowToImageFilter  # noqa: E402
import vtkmodules.vtkRenderingOpenGL2  # noqa: E402,F401 (the OpenGL render window)

ap = argparse.ArgumentParser()
ap.add_argument("--input", required=True)
ap.add_argument("--output", default="hybrid-octree-mapper.png")
ap.add_argument("--reference", help="the CLI's full-resolution reference PNG of the same scene")
ap.add_argument("--budget-mb", type=float, default=64.0)
ap.add_argument("--isovalue", type=float, default=0.5)
ap.add_argument("--surface-opacity", type=float, default=0.4)
args = ap.parse_args()

reader = vtkXMLImageDataReader()
reader.SetFileName(args.input)
reader.Update()
image = reader.GetOutput()
mapper = vtkHybridOctreeVolumeMapper()
mapper.SetInputData(image)
mapper.SetBudgetMB(args.budget_mb)
mapper.ShowSurfaceOn()
mapper.SetIsovalue(args.isovalue)
mapper.SetSurfaceColor(0.9, 0.75, 0.55)
mapper.SetSurfaceOpacity(args.surface_opacity)
volume = vtkVolume()
volume.SetMapper(mapper)
volume.SetProperty(volume_property(image))
renderer = vtkRenderer()
renderer.SetBackground(*BACKGROUND)
renderer.AddVolume(volume)
look_around(renderer, image.GetBounds(), 30.0)
renderer.ResetCameraClippingRange()
window = vtkRenderWindow()
window.SetOffScreenRendering(1)
window.SetSize(512, 512)
window.AddRenderer(renderer)
window.Render()  # builds the octree, selects, uploads
window.Render()  # a frame from resident textures
if not mapper.GetLastRenderOK():
    sys.exit("the mapper did not draw (see the error above)")
grab = vtkWindowToImageFilter()
grab.SetInput(window)
grab.SetInputBufferTypeToRGB()
grab.ReadFrontBufferOff()
writer = vtkPNGWriter()
writer.SetFileName(args.output)
writer.SetInputConnection(grab.GetOutputPort())
writer.Write()
print(f"vtkHybridOctreeVolumeMapper: {mapper.GetLastBricks()} bricks, "
      f"{mapper.GetLastTextureBytes() / 1e6:.1f} MB of textures (budget {args.budget_mb:g} MB), "
      f"plan '{mapper.GetLastPlan()}', {mapper.GetLastSurfaceTriangles()} surface triangles drawn, "
      f"frame {mapper.GetLastFrameMilliseconds():.0f} ms, estimated error {mapper.GetLastEstimatedError():.4f}")
if args.reference:
    rmse = float(np.sqrt(np.mean((png_rgb(args.output) - png_rgb(args.reference)) ** 2)))
    print(f"RMSE against the full-resolution reference ({args.reference}): {rmse:.4f}")
print(f"wrote {args.output}")
