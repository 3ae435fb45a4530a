"""What both side-by-side benchmarks share: every core for VTK, the median
timer, a built-in dataset read back as ParaView reads it, and the
FlyingEdges baseline. Imported by the bench/*_vs_flying_edges.py scripts
(pvpython puts the script's folder on sys.path)."""
import os
import statistics
import subprocess
import time

from vtkmodules.vtkCommonCore import vtkMultiThreader, vtkSMPTools
from vtkmodules.vtkFiltersCore import vtkFlyingEdges3D
from vtkmodules.vtkIOXML import vtkXMLImageDataReader


def use_all_cores():
    """pvpython starts VTK on one thread (Sequential SMP backend): switch to
    STDThread with the thread limit at the core count, as rayon uses all
    cores for ours. Returns the core count."""
    cores = os.cpu_count()
    vtkSMPTools.SetBackend("STDThread")
    vtkSMPTools.Initialize(cores)
    vtkMultiThreader.SetGlobalMaximumNumberOfThreads(cores)
    return cores


def median_ms(fn, repeats):
    """Median wall time of `repeats` calls of `fn`, in ms, after one untimed warm-up."""
    fn()
    times = []
    for _ in range(repeats):
        t = time.perf_counter()
        fn()
        times.append((time.perf_counter() - t) * 1e3)
    return statistics.median(times)


def generated_image(cli, dataset, size, scalar_type, path):
    """Writes a built-in dataset with the CLI to `path` (.vti) and reads it with VTK."""
    subprocess.run([cli, "generate", "--dataset", dataset, "--size", str(size), "--type", scalar_type,
                    "--output", path], check=True, capture_output=True)
    reader = vtkXMLImageDataReader()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


def time_flying_edges(image, isovalue, repeats):
    """vtkFlyingEdges3D on `image` at `isovalue`, without normals (its fastest
    mode): (median ms, the filter holding its last output)."""
    fe = vtkFlyingEdges3D()
    fe.SetInputData(image)
    fe.SetValue(0, isovalue)
    fe.ComputeNormalsOff()

    def run():
        fe.Modified()
        fe.Update()
    return median_ms(run, repeats), fe
