"""The Python-wrapped Hybrid Octree classes in pvpython/pvbatch: the same
pipeline a C++ program builds (tests/consumer), checked end to end.

    PYTHONPATH=<build>/lib/python3.11/site-packages pvpython tests/python/test_pipeline.py

1. vtkRTAnalyticSource (65^3 wavelet) -> vtkHybridOctreeFilter: boxes of the
   cut and the isosurface with its field data.
2. The same source -> vtkHybridOctreeVolumeMapper in a vtkVolume, a 200x200
   offscreen window, a translucent isosurface: the frame draws within the
   budget, the plan names the surface pass, and the picture shows the volume
   (between 5 % and 95 % of the pixels differ from the background).
3. A mapper with no input: Render() reports the error (captured from the
   ErrorEvent) and nothing is drawn.
4. NaN is no data: the wavelet with a NaN ball builds in the filter (field
   data "nan_samples") and draws in the mapper (GetLastNaNSamples) without
   an error event.
Exits non-zero, with the reason, on any failed check.
"""
import sys

from hybrid_octree import vtkHybridOctreeFilter, vtkHybridOctreeVolumeMapper
from vtkmodules.vtkCommonCore import vtkCommand
from vtkmodules.vtkImagingCore import vtkRTAnalyticSource
from vtkmodules.vtkRenderingCore import (vtkColorTransferFunction, vtkRenderer, vtkRenderWindow,
                                         vtkVolume, vtkVolumeProperty, vtkWindowToImageFilter)
from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (the OpenGL render window)

failures = []


def check(condition, what):
    print(("ok   " if condition else "FAIL ") + what)
    if not condition:
        failures.append(what)


source = vtkRTAnalyticSource()
source.SetWholeExtent(-32, 32, -32, 32, -32, 32)
source.Update()
lo, hi = source.GetOutput().GetPointData().GetScalars().GetRange()

# 1. The filter.
octree = vtkHybridOctreeFilter()
octree.SetInputConnection(source.GetOutputPort())
octree.SetLeafSize(8)
octree.SetIsovalue(0.5 * (lo + hi))
octree.Update()
boxes = octree.GetOutput(0)
surface = octree.GetOutput(1)
cut = boxes.GetFieldData().GetArray("cut_count").GetValue(0)
check(cut > 0 and boxes.GetNumberOfPoints() == 8 * cut, f"the filter cut the octree into {cut} boxes")
check(surface.GetNumberOfPolys() > 0, f"the isosurface has {surface.GetNumberOfPolys()} triangles")
iso = surface.GetFieldData().GetArray("isovalue").GetValue(0)
check(iso == 0.5 * (lo + hi), f"the surface's isovalue field is {iso}")

# 2. The mapper.
budget_mb = 0.5
mapper = vtkHybridOctreeVolumeMapper()
mapper.SetInputConnection(source.GetOutputPort())
mapper.SetLeafSize(8)
mapper.SetBudgetMB(budget_mb)
mapper.ShowSurfaceOn()
mapper.SetIsovalue(lo + 0.75 * (hi - lo))
mapper.SetSurfaceColor(1.0, 0.9, 0.7)
mapper.SetSurfaceOpacity(0.5)
color = vtkColorTransferFunction()
color.AddRGBPoint(lo, 0.1, 0.2, 0.9)
color.AddRGBPoint(hi, 0.9, 0.1, 0.1)
opacity = vtkPiecewiseFunction()
opacity.AddPoint(0.5 * (lo + hi), 0.0)
opacity.AddPoint(hi, 0.3)
prop = vtkVolumeProperty()
prop.SetColor(color)
prop.SetScalarOpacity(opacity)
volume = vtkVolume()
volume.SetMapper(mapper)
volume.SetProperty(prop)
renderer = vtkRenderer()
renderer.SetBackground(0.0, 0.0, 0.0)
renderer.AddVolume(volume)
window = vtkRenderWindow()
window.SetOffScreenRendering(1)
window.SetSize(200, 200)
window.AddRenderer(renderer)
renderer.ResetCamera()
window.Render()
check(mapper.GetLastRenderOK(), "the mapper drew")
check(mapper.GetLastBricks() > 0, f"{mapper.GetLastBricks()} bricks")
check(0 < mapper.GetLastTextureBytes() <= budget_mb * 1e6,
      f"{mapper.GetLastTextureBytes()} texture bytes within {budget_mb} MB")
check(mapper.GetLastPlan() == "surface-in-slabs,volume", f"plan '{mapper.GetLastPlan()}'")
check(mapper.GetLastSurfaceTriangles() > 0, f"{mapper.GetLastSurfaceTriangles()} surface triangles")
grab = vtkWindowToImageFilter()
grab.SetInput(window)
grab.ReadFrontBufferOff()
grab.Update()
pixels = grab.GetOutput().GetPointData().GetScalars()
n = pixels.GetNumberOfTuples()
lit = sum(1 for i in range(n) if max(pixels.GetTuple(i)[:3]) > 8)
check(0.05 < lit / n < 0.95, f"{100.0 * lit / n:.1f} % of the pixels show the volume")

# 3. Bad input: an error event, nothing drawn.
empty = vtkHybridOctreeVolumeMapper()
messages = []


def on_error(caller, event, data=None):
    messages.append(str(data))


on_error.CallDataType = "string0"
empty.AddObserver(vtkCommand.ErrorEvent, on_error)
empty.Render(renderer, volume)
check(not empty.GetLastRenderOK(), "a mapper without input draws nothing")
check(any("no input" in m for m in messages), f"its error says 'no input': {messages}")

# 4. NaN samples: no data, not an error.
import numpy as np  # noqa: E402 (pvpython ships numpy)
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkImageData  # noqa: E402

holed = vtkImageData()
holed.DeepCopy(source.GetOutput())
values = vtk_to_numpy(holed.GetPointData().GetScalars())  # a view: writes go to the image
z, y, x = np.mgrid[-32:33, -32:33, -32:33]
ball = ((x - 10) ** 2 + y ** 2 + z ** 2 <= 100).ravel()
values[ball] = np.nan
holed.GetPointData().GetScalars().Modified()
nan_count = int(ball.sum())
octree.SetInputData(holed)
octree.Update()
counted = octree.GetOutput(0).GetFieldData().GetArray("nan_samples").GetValue(0)
check(counted == nan_count, f"the filter counts {counted} NaN samples of {nan_count}")
check(octree.GetOutput(1).GetNumberOfPolys() > 0, "the isosurface around the NaN ball")
mapper.SetInputData(holed)
messages.clear()
mapper.AddObserver(vtkCommand.ErrorEvent, on_error)
window.Render()
check(mapper.GetLastRenderOK() and not messages, f"the mapper draws the NaN ball without an error: {messages}")
check(mapper.GetLastNaNSamples() == nan_count, f"the mapper counts {mapper.GetLastNaNSamples()} NaN samples")

print("PASS" if not failures else f"{len(failures)} check(s) failed")
sys.exit(1 if failures else 0)
