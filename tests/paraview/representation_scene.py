"""The scene the representation tests draw: a volume shown with a given
representation type in a fixed colour map, opacity function and camera.

Used by test_representation.py (one process) and mpi_scene.py (under
mpiexec), so that every image compared was drawn the same way.
"""
from paraview.simple import (ColorBy, CreateView, GetColorTransferFunction,
                             GetOpacityTransferFunction, Render, Show)

SIZE = (320, 320)


def make_view(size=SIZE):
    view = CreateView("RenderView")
    view.ViewSize = list(size)
    view.OrientationAxesVisibility = 0
    view.Background = [0.1, 0.1, 0.15]
    # A plain background colour, not the palette's gradient.
    if hasattr(view, "UseColorPaletteForBackground"):
        view.UseColorPaletteForBackground = 0
    return view


def show_volume(source, view, array, representation, value_range):
    """Shows `source` in `view` as `representation` ("Volume" or "Hybrid
    Octree Volume"), coloured by point array `array` over `value_range`."""
    display = Show(source, view)
    display.SetRepresentationType(representation)
    ColorBy(display, ("POINTS", array))
    lo, hi = value_range
    lut = GetColorTransferFunction(array)
    lut.RGBPoints = [lo, 0.23, 0.30, 0.75, 0.5 * (lo + hi), 0.87, 0.87, 0.87, hi, 0.71, 0.02, 0.15]
    lut.ColorSpace = "RGB"
    pwf = GetOpacityTransferFunction(array)
    w = hi - lo
    pwf.Points = [lo, 0.0, 0.5, 0.0, lo + 0.1 * w, 0.0, 0.5, 0.0, lo + 0.3 * w, 0.02, 0.5, 0.0,
                  hi, 0.25, 0.5, 0.0]
    lut.AutomaticRescaleRangeMode = "Never"
    lut.RescaleTransferFunction(lo, hi)
    pwf.RescaleTransferFunction(lo, hi)
    return display


def look_at(view, bounds):
    """A fixed oblique perspective view of `bounds` (xmin, xmax, ...)."""
    # paraview.simple.Render resets the camera on a view's first render:
    # render once before placing it.
    Render(view)
    c = [0.5 * (bounds[2 * a] + bounds[2 * a + 1]) for a in range(3)]
    r = max(bounds[2 * a + 1] - bounds[2 * a] for a in range(3))
    view.CameraFocalPoint = c
    view.CameraPosition = [c[0] + 1.6 * r, c[1] - 1.2 * r, c[2] + 0.9 * r]
    view.CameraViewUp = [0.0, 0.0, 1.0]
    view.CameraViewAngle = 30.0
    view.CameraParallelProjection = 0
    Render(view)
