"""What the pvbatch effect tests (test_shade.py, test_isosurface.py,
test_crop.py) share: their arguments (--plugin, --cli, --workdir), the
plugin loaded, a phantom read, screenshots into the work folder, and the
representation's read-only statistics (LastPlan, LastEffects).
"""
import argparse
import os

from paraview.simple import LoadPlugin, SaveScreenshot, XMLImageDataReader
from pvtest import generate_phantom, read_png_rgb
from representation_scene import SIZE


class EffectTest:
    """The arguments parsed, the plugin loaded and a `size`^3 phantom read:
    `reader`, its first point array `array`, its `value_range` and `bounds`."""

    def __init__(self, size=64):
        parser = argparse.ArgumentParser()
        parser.add_argument("--plugin", required=True)
        parser.add_argument("--cli", required=True)
        parser.add_argument("--workdir", required=True)
        self.args = parser.parse_args()
        os.makedirs(self.args.workdir, exist_ok=True)
        LoadPlugin(self.args.plugin, remote=False)
        self.reader = XMLImageDataReader(FileName=[generate_phantom(self.args.cli, self.args.workdir, size)])
        self.reader.UpdatePipeline()
        self.array = self.reader.PointData.keys()[0]
        self.value_range = self.reader.PointData[self.array].GetRange()
        self.bounds = self.reader.GetDataInformation().GetBounds()

    def screenshot(self, view, name, size=SIZE):
        """The view saved as <workdir>/<name>.png at `size` pixels, read back as RGB."""
        path = os.path.join(self.args.workdir, name + ".png")
        SaveScreenshot(path, view, ImageResolution=list(size))
        return read_png_rgb(path)


def statistic(display, name):
    """The representation's read-only property `name` after the last frame."""
    display.SMProxy.UpdatePropertyInformation()
    return display.GetPropertyValue(name)
