"""What the pvbatch tests share: checks that collect failures, a log of VTK's
error output the script can read, and images compared by RMSE.

pvbatch routes sys.stderr (and Python tracebacks) through vtkOutputWindow,
which `Checks.log_vtk_output` redirects to a file; reports go to the
process's stdout directly.
"""
import os
import sys

from vtkmodules.vtkCommonCore import vtkFileOutputWindow, vtkOutputWindow


def report(text):
    os.write(1, (text + "\n").encode())


class Checks:
    def __init__(self, name):
        self.name = name
        self.failures = []
        self.error_log = None
        sys.excepthook = self._on_exception

    def check(self, condition, what):
        """Records `what` as failed unless `condition`; returns `condition`."""
        if not condition:
            self.failures.append(what)
            report("FAILED: " + what)
        return condition

    def log_vtk_output(self, path):
        """Sends VTK's error and warning output to `path` (read with `logged`)."""
        self.error_log = path
        if os.path.exists(path):
            os.remove(path)
        window = vtkFileOutputWindow()
        window.SetFileName(path)
        window.SetFlush(1)
        vtkOutputWindow.SetInstance(window)

    def logged(self):
        """Everything VTK wrote to its output window so far."""
        if not self.error_log or not os.path.exists(self.error_log):
            return ""
        with open(self.error_log) as f:
            return f.read()

    def finish(self):
        """Reports the result; call it last. On failure the process exits 1
        at once; on success the script must simply end. sys.exit() after
        rendering makes pvbatch 5.11 crash in its teardown (SIGSEGV, or an
        X error from a render view's destructor), whatever was drawn."""
        if self.failures:
            report("%d check(s) failed" % len(self.failures))
            os._exit(1)
        report(self.name + " passed")

    def _on_exception(self, kind, value, tb):
        import traceback
        report("".join(traceback.format_exception(kind, value, tb)))
        report("VTK output window log:\n" + self.logged()[-2000:])
        os._exit(1)


def read_png_rgb(path):
    """The PNG at `path` as an (h*w, 3) float array in [0, 1]."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOImage import vtkPNGReader

    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    pixels = vtk_to_numpy(reader.GetOutput().GetPointData().GetScalars())
    return pixels[:, :3].astype(float) / 255.0


def window_rgb(view, png=None):
    """The picture `view`'s window holds now (not rendered again), as an
    (h*w, 3) float array in [0, 1] like read_png_rgb; also written to `png`."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOImage import vtkPNGWriter
    from vtkmodules.vtkRenderingCore import vtkWindowToImageFilter

    grab = vtkWindowToImageFilter()
    grab.SetInput(view.GetRenderWindow())
    grab.SetInputBufferTypeToRGB()
    grab.ReadFrontBufferOff()
    grab.ShouldRerenderOff()
    grab.Update()
    if png:
        writer = vtkPNGWriter()
        writer.SetFileName(png)
        writer.SetInputData(grab.GetOutput())
        writer.Write()
    return vtk_to_numpy(grab.GetOutput().GetPointData().GetScalars()).astype(float) / 255.0


def rmse(a, b):
    """Root mean square difference of two RGB images (same size), in [0, 1]."""
    import numpy as np

    if a.shape != b.shape:
        return float("inf")
    return float(np.sqrt(((a - b) ** 2).mean()))


def generate_phantom(cli, workdir, size):
    """Writes the CLI's size^3 Shepp-Logan phantom (f32) to workdir; returns the path."""
    import subprocess

    path = os.path.join(workdir, "phantom%d.vti" % size)
    subprocess.run([cli, "generate", "--dataset", "shepp-logan", "--size", str(size), "--output", path],
                   check=True, capture_output=True)
    return path
