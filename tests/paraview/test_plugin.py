"""pvbatch test of the HybridOctree ParaView plugin.

    pvbatch test_plugin.py --cli <hybrid-octree> --workdir <dir> (--plugin <HybridOctree.so> | --autoload)

With --plugin the script loads the plugin with LoadPlugin; with --autoload it
expects ParaView to have loaded it already (PV_PLUGIN_CONFIG_FILE naming the
auto-load plugins XML). It then checks, against the command line tool's JSON
on the same files, the field data of the filter on Wavelet() and on a sphere
volume the CLI generates; that changing only the tolerance does not rebuild;
the isosurface on output port 1 in both surface modes against
`hybrid-octree surface --json`, and that ParaView defaults the Isovalue to the
middle of the data range; that NaN samples are no data (the filter builds
and counts them in the field data "nan_samples") while an infinite sample
fails with the core's message and pvbatch keeps running; and that the input domain refuses an
unstructured grid. Exits non-zero after all checks if any failed.
"""
import argparse
import json
import math
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from paraview import servermanager  # noqa: E402
from paraview.simple import *  # noqa: E402,F401,F403 (pvbatch scripting API)
from paraview.vtk.util.numpy_support import numpy_to_vtk  # noqa: E402
from pvtest import Checks, report  # noqa: E402

parser = argparse.ArgumentParser()
parser.add_argument("--cli", required=True)
parser.add_argument("--workdir", required=True)
parser.add_argument("--plugin")
parser.add_argument("--autoload", action="store_true")
args = parser.parse_args()
os.makedirs(args.workdir, exist_ok=True)

t = Checks("HybridOctree plugin test")
check, finish = t.check, t.finish


# ---- Loading ------------------------------------------------------------------
if args.autoload:
    check("HybridOctree" in globals(), "HybridOctree auto-loaded through PV_PLUGIN_CONFIG_FILE")
    if "HybridOctree" not in globals():
        finish()
else:
    LoadPlugin(args.plugin, remote=False, ns=globals())
    check("HybridOctree" in globals(), "LoadPlugin defines HybridOctree")

# Errors of the filters go to this file, so the script can read them.
t.log_vtk_output(os.path.join(args.workdir, "vtk-errors.txt"))
logged_errors = t.logged


def field_data(proxy, port=0):
    """The data on output `port` and its field data: numbers, and strings for string arrays."""
    data = servermanager.Fetch(proxy, idx=port)
    fd = data.GetFieldData()
    values = {}
    for i in range(fd.GetNumberOfArrays()):
        array = fd.GetAbstractArray(i)
        values[array.GetName()] = array.GetValue(0) if array.IsA("vtkStringArray") else array.GetTuple1(0)
    return data, values


def cli_json(path, leaf, tolerance):
    out = subprocess.run(
        [args.cli, "build", "--file", path, "--leaf-size", str(leaf), "--tolerance", repr(tolerance), "--json"],
        check=True, capture_output=True, text=True).stdout
    return json.loads(out)


EXACT = ["node_count", "terminal_count", "homogeneous_count", "levels", "leaf_size", "root_size",
         "octree_bytes", "input_bytes", "value_min", "value_max", "cut_count"]


def compare_with_cli(name, source, path, leaf, tolerance):
    source.UpdatePipeline()
    octree = HybridOctree(Input=source)
    octree.LeafSize = leaf
    octree.ErrorTolerance = tolerance
    octree.UpdatePipeline()
    data, fd = field_data(octree)
    expected = cli_json(path, leaf, tolerance)
    for key in EXACT:
        check(key in fd and fd[key] == expected[key],
              "%s: %s = %s, CLI says %s" % (name, key, fd.get(key), expected[key]))
    check(data.GetNumberOfPoints() == 8 * expected["cut_count"], name + ": 8 points per box")
    check(data.GetNumberOfLines() == 12 * expected["cut_count"], name + ": 12 lines per box")
    return octree, fd


# ---- Wavelet, saved for the CLI ------------------------------------------------
wavelet = Wavelet()
wavelet.WholeExtent = [-12, 12, -12, 12, -12, 12]
wavelet_vti = os.path.join(args.workdir, "wavelet.vti")
# ParaView's default encoding (appended raw), which the CLI reads as users' files.
SaveData(wavelet_vti, proxy=wavelet)
octree, fd = compare_with_cli("wavelet", wavelet, wavelet_vti, 4, 0.02)
check(octree.Scalars == ["POINTS", "RTData"], "the Scalars domain picks RTData: %s" % (octree.Scalars,))

# Only the tolerance changes: the cached octree is re-cut, not rebuilt.
octree.ErrorTolerance = 0.2
octree.UpdatePipeline()
_, coarse = field_data(octree)
check(coarse["build_ms"] == fd["build_ms"], "a tolerance change keeps the octree (same build_ms)")
check(coarse["cut_count"] == cli_json(wavelet_vti, 4, 0.2)["cut_count"], "cut at 0.2 matches the CLI")
check(coarse["cut_count"] < fd["cut_count"], "a larger tolerance gives a coarser cut")
Delete(octree)

# ---- A sphere volume written by the CLI --------------------------------------
sphere_vti = os.path.join(args.workdir, "sphere.vti")
subprocess.run([args.cli, "generate", "--dataset", "sphere", "--size", "40", "--type", "f32",
                "--output", sphere_vti], check=True, capture_output=True)
sphere = XMLImageDataReader(FileName=[sphere_vti])
for leaf, tolerance in [(8, 0.01), (4, 0.0), (16, 0.05)]:
    o, _ = compare_with_cli("sphere leaf %d tol %g" % (leaf, tolerance), sphere, sphere_vti, leaf, tolerance)
    Delete(o)

# ---- Progress and abort --------------------------------------------------------
# ParaView's progress bar and abort button act on the VTK object: its
# ProgressEvent, and SetAbortExecute from the progress handler.
big = Wavelet(WholeExtent=[0, 95, 0, 95, 0, 95])
big.UpdatePipeline()
watched = HybridOctree(Input=big, LeafSize=4, MeasureSurfaceDistance=0)
vtk_filter = watched.GetClientSideObject()
progress_values = []
abort_first = [False]


def on_progress(obj, event):
    progress_values.append(obj.GetProgress())
    if abort_first[0] and len(progress_values) == 1:
        obj.SetAbortExecute(1)


vtk_filter.AddObserver("ProgressEvent", on_progress)
watched.UpdatePipeline()
inside = [v for v in progress_values if 0.0 < v < 1.0]
check(len(inside) >= 20 and inside == sorted(inside), "the build reports progress: %d values" % len(inside))
check(progress_values and progress_values[-1] == 1.0, "progress ends at 1")
_, full = field_data(watched)

Delete(watched)
watched = HybridOctree(Input=big, LeafSize=4, MeasureSurfaceDistance=0)
vtk_filter = watched.GetClientSideObject()
vtk_filter.AddObserver("ProgressEvent", on_progress)
progress_values.clear()
abort_first[0] = True
watched.UpdatePipeline()
cancelled_data, cancelled = field_data(watched)
# ParaView may run the aborted filter more than once (an ABORTED output is out
# of date); every run must stop at its first chunk of leaf bricks.
inside = [v for v in progress_values if 0.0 < v < 1.0]
check(inside and max(inside) <= 0.02, "an abort stops the build at once: %s" % progress_values)
check(cancelled_data.GetNumberOfPoints() == 0 and not cancelled, "the cancelled request's output is empty")
check("cancelled" in logged_errors(), "the cancel is reported in the output messages")
abort_first[0] = False
vtk_filter.SetAbortExecute(0)
watched.ErrorTolerance = 0.02  # what a user does after an abort: change a property, Apply
watched.UpdatePipeline()
check(field_data(watched)[0].GetNumberOfPoints() > 0, "after the abort, Apply builds")
watched.ErrorTolerance = 0.01
watched.UpdatePipeline()
_, again = field_data(watched)
check(again.get("node_count") == full["node_count"] and again.get("cut_count") == full["cut_count"],
      "after the abort the next update builds the same octree: %s vs %s"
      % (again.get("node_count"), full["node_count"]))
Delete(watched)
Delete(big)

# ---- The depth image of the binary octree (paper 2) -------------------------------
# Same counters as the CLI on the same file, and the same depth front to back
# and back to front.
depth_inputs = XMLImageDataReader(FileName=[sphere_vti])
depth_inputs.UpdatePipeline()
sphere_array = ["POINTS", depth_inputs.PointData.keys()[0]]
ftb_proxy = HybridOctreeDepthImage(Input=depth_inputs, Scalars=sphere_array, Isovalue=0.5,
                                   ViewPlaneNormal=[1, -2, 1], ImageSize=64)
ftb_proxy.UpdatePipeline()
ftb_image = servermanager.Fetch(ftb_proxy)
btf_proxy = HybridOctreeDepthImage(Input=depth_inputs, Scalars=sphere_array, Isovalue=0.5,
                                   ViewPlaneNormal=[1, -2, 1], ImageSize=64, Method="Back To Front")
btf_proxy.UpdatePipeline()
btf_image = servermanager.Fetch(btf_proxy)
check(ftb_image.GetDimensions() == (64, 64, 1), "the depth image is 64 x 64: %s" % (ftb_image.GetDimensions(),))
from paraview.vtk.util.numpy_support import vtk_to_numpy  # noqa: E402
ftb_depth = vtk_to_numpy(ftb_image.GetPointData().GetArray("depth"))
btf_depth = vtk_to_numpy(btf_image.GetPointData().GetArray("depth"))
check(ftb_depth.tobytes() == btf_depth.tobytes(), "front to back and back to front give the same depth")
import numpy  # noqa: E402  (pvbatch ships numpy)
check(int((~numpy.isnan(ftb_depth)).sum()) > 100, "the sphere is seen in the depth image")
cli_rows = subprocess.run(
    [args.cli, "ftb", "--file", sphere_vti, "--isovalue", "0.5", "--vpn", "1,-2,1", "--image-size", "64",
     "--repeats", "1", "--output", os.path.join(args.workdir, "ftb"), "--json"],
    check=True, capture_output=True, text=True).stdout
cli_row = json.loads(cli_rows.splitlines()[0])
ftb_fd = ftb_image.GetFieldData()
for key in ["faces", "scanlines", "pixels", "black_visited", "white_visited", "gray_visited"]:
    check(ftb_fd.GetArray(key).GetValue(0) == cli_row["ftb"][key],
          "depth image %s = %s, the CLI says %s" % (key, ftb_fd.GetArray(key).GetValue(0), cli_row["ftb"][key]))
    check(btf_image.GetFieldData().GetArray(key).GetValue(0) == cli_row["btf"][key], "BTF %s matches the CLI" % key)
Delete(btf_proxy)
Delete(ftb_proxy)

# ---- Hybrid Octree Points: the same points as the CLI's point file ----------------
points_file = os.path.join(args.workdir, "sphere-points.hop")
points_proxy = HybridOctreePoints(Input=depth_inputs, Scalars=sphere_array, Factor=4, Threshold=0.01,
                                  FileName=points_file)
points_proxy.UpdatePipeline()
point_cloud = servermanager.Fetch(points_proxy)
n_points = point_cloud.GetNumberOfPoints()
check(n_points > 0, "Hybrid Octree Points makes points: %d" % n_points)
check(point_cloud.GetPointData().GetArray("error") is not None, "the points carry their error")
check(point_cloud.GetFieldData().GetArray("point_bytes").GetValue(0) == 6 * n_points, "6 bytes a point")
cli_points = json.loads(subprocess.run(
    [args.cli, "points", "--file", sphere_vti, "--factor", "4", "--threshold", "0.01",
     "--output", os.path.join(args.workdir, "sphere-cli.hop"), "--json"],
    check=True, capture_output=True, text=True).stdout)
check(cli_points["points"] == n_points, "the CLI makes %d points, the proxy %d" % (cli_points["points"], n_points))
with open(points_file, "rb") as a, open(os.path.join(args.workdir, "sphere-cli.hop"), "rb") as b:
    check(a.read() == b.read(), "the proxy's point file equals the CLI's, byte for byte")
points_proxy.Factor = 3
points_proxy.UpdatePipeline()
check(servermanager.Fetch(points_proxy).GetNumberOfPoints() == 0, "factor 3 fails with an empty output")
Delete(points_proxy)
Delete(depth_inputs)

# ---- The isosurface on output port 1 -------------------------------------------
SURFACE_EXACT = ["polygons", "faces", "triangles", "uncompressed_triangles", "vertices", "boundary_edges"]


def cli_surface_json(path, isovalue, mode, leaf):
    out = subprocess.run(
        [args.cli, "surface", "--file", path, "--isovalue", repr(isovalue), "--mode", mode,
         "--leaf-size", str(leaf), "--distance", "--json"],
        check=True, capture_output=True, text=True).stdout
    return json.loads(out)


surface_octree = HybridOctree(Input=sphere)
check(surface_octree.SMProxy.GetOutputPortName(0) == "Boxes", "output port 0 is named Boxes")
check(surface_octree.SMProxy.GetOutputPortName(1) == "Surface", "output port 1 is named Surface")
# ParaView sets the Isovalue from the ArrayRangeDomain: the middle of the range.
sphere_range = sphere.PointData[sphere.PointData.keys()[0]].GetRange()
check(abs(surface_octree.Isovalue - 0.5 * (sphere_range[0] + sphere_range[1])) <= 1e-12 * sphere_range[1],
      "default Isovalue %r is the middle of the range %r" % (surface_octree.Isovalue, sphere_range))
check(surface_octree.SurfaceMode == "Discretized", "default Surface Mode is Discretized")
check(surface_octree.MeasureSurfaceDistance == 1, "the distance is measured by default")
surface_octree.LeafSize = 8
triangles = {}
for isovalue in (0.5, surface_octree.Isovalue):
    for mode in ("Discretized", "Interpolated"):
        name = "sphere surface %s at %g" % (mode, isovalue)
        surface_octree.Isovalue = isovalue
        surface_octree.SurfaceMode = mode
        surface_octree.UpdatePipeline()
        surface, fd = field_data(surface_octree, 1)
        expected = cli_surface_json(sphere_vti, isovalue, mode.lower(), 8)
        check(fd.get("polygons", 0) > 0, name + ": has polygons")
        check(fd.get("boundary_edges") == 0, name + ": closed (boundary_edges 0)")
        for key in SURFACE_EXACT:
            check(key in fd and fd[key] == expected[key],
                  "%s: %s = %s, CLI says %s" % (name, key, fd.get(key), expected[key]))
        check(surface.GetNumberOfPolys() == fd.get("polygons"), name + ": one cell per polygon")
        check(surface.GetNumberOfPoints() == fd.get("vertices"), name + ": one point per vertex")
        normals = surface.GetPointData().GetNormals()
        check(normals is not None and normals.GetName() == "Normals" and normals.GetNumberOfComponents() == 3,
              name + ": point normals 'Normals'")
        for array in ("node", "level"):
            a = surface.GetCellData().GetArray(array)
            check(a is not None and a.GetNumberOfTuples() == surface.GetNumberOfPolys(),
                  name + ": cell array " + array)
        check(fd.get("surface_mode") == mode.lower(), name + ": surface_mode %r" % fd.get("surface_mode"))
        check(fd.get("isovalue") == isovalue, name + ": field isovalue")
        check(0 < fd.get("distance_max", -1) <= 0.5 * math.sqrt(3) and
              0 < fd.get("distance_mean", -1) <= fd.get("distance_max", -1),
              name + ": distance mean %r, max %r voxels" % (fd.get("distance_mean"), fd.get("distance_max")))
        for key in ("distance_mean", "distance_max"):
            check(abs(fd.get(key, -1) - expected[key]) <= 1e-9 * abs(expected[key]),
                  "%s: %s = %r, CLI says %r" % (name, key, fd.get(key), expected[key]))
        triangles[mode] = fd.get("triangles")
    check(triangles["Discretized"] < triangles["Interpolated"],
          "isovalue %g: DiscMC has fewer triangles (%r) than the interpolated surface (%r)"
          % (isovalue, triangles["Discretized"], triangles["Interpolated"]))
    report("sphere at %g: triangles %r" % (isovalue, triangles))

# The boxes on port 0 are unchanged by the surface, and a tolerance change
# reuses the cached surface (same extract_ms).
_, before = field_data(surface_octree, 1)
surface_octree.ErrorTolerance = 0.2
surface_octree.UpdatePipeline()
_, after = field_data(surface_octree, 1)
_, boxes = field_data(surface_octree, 0)
check(after["extract_ms"] == before["extract_ms"], "a tolerance change keeps the surface (same extract_ms)")
check(boxes["cut_count"] == cli_json(sphere_vti, 8, 0.2)["cut_count"], "port 0 still matches the CLI")
# An isovalue outside the data range: an empty surface, no error.
errors_before = len(logged_errors())
surface_octree.Isovalue = sphere_range[1] + 1.0
surface_octree.UpdatePipeline()
empty, fd = field_data(surface_octree, 1)
check(empty.GetNumberOfPoints() == 0 and fd.get("polygons") == 0, "isovalue above the range: empty surface")
check(len(logged_errors()) == errors_before, "isovalue above the range: no error")
Delete(surface_octree)

# ---- Bad input: each fails the request with the core's or the filter's message --
import numpy as np  # noqa: E402  (pvbatch ships numpy)
from vtkmodules.vtkCommonDataModel import vtkImageData  # noqa: E402


def image(dims, point_values=None, cell_values=None, components=1):
    """A vtkImageData of `dims` with optional point and cell arrays."""
    img = vtkImageData()
    img.SetDimensions(*dims)
    for values, data in ((point_values, img.GetPointData()), (cell_values, img.GetCellData())):
        if values is not None:
            arr = numpy_to_vtk(values.reshape(-1, components) if components > 1 else values, deep=1)
            arr.SetName("f")
            data.SetScalars(arr)
    return img


def expect_failure(name, img, message):
    """The filter on `img` gives an empty output and `message` in the error log."""
    before = len(logged_errors())
    source = TrivialProducer()
    source.GetClientSideObject().SetOutput(img)
    source.UpdatePipeline()
    bad = HybridOctree(Input=source)
    bad.UpdatePipeline()
    for port in (0, 1):
        out = servermanager.Fetch(bad, idx=port)
        check(out.GetNumberOfPoints() == 0 and out.GetFieldData().GetNumberOfArrays() == 0,
              "%s: empty output on port %d" % (name, port))
    new_errors = logged_errors()[before:]
    check(message in new_errors, "%s: error %r not in %r" % (name, message, new_errors[-400:]))
    Delete(bad)
    Delete(source)


# NaN is no data: the filter builds, counts them, and leaves them out of the range.
nan_values = np.linspace(0.0, 1.0, 6 * 6 * 6).astype(np.float32)
nan_values[10] = np.nan
nan_values[20:26] = np.nan
before = len(logged_errors())
nan_source = TrivialProducer()
nan_source.GetClientSideObject().SetOutput(image((6, 6, 6), nan_values))
nan_source.UpdatePipeline()
nan_octree = HybridOctree(Input=nan_source)
nan_octree.UpdatePipeline()
nan_out, nan_fd = field_data(nan_octree, 0)
check(len(logged_errors()) == before, "NaN volume: no error: %r" % logged_errors()[before:][-400:])
check(nan_fd.get("nan_samples") == 7, "NaN volume: nan_samples %r" % nan_fd.get("nan_samples"))
check(nan_fd.get("value_min") == 0.0 and nan_fd.get("value_max") == 1.0,
      "NaN volume: the range leaves NaN out: %r .. %r" % (nan_fd.get("value_min"), nan_fd.get("value_max")))
check(nan_out.GetNumberOfPoints() > 0, "NaN volume: the boxes of the cut")
Delete(nan_octree)
Delete(nan_source)
inf_values = np.linspace(0.0, 1.0, 6 * 6 * 6).astype(np.float32)
inf_values[5] = np.nan
inf_values[10] = np.inf
expect_failure("infinite sample", image((6, 6, 6), inf_values),
               "1 infinite sample(s), the first at point index 10")
expect_failure("NaN only", image((6, 6, 6), np.full(216, np.nan, np.float32)), "no data: all 216 samples are NaN")
expect_failure("no scalars", image((6, 6, 6)), "no point scalars")
expect_failure("cell scalars only", image((6, 6, 6), cell_values=np.ones(125, np.float32)),
               "cell data only: point scalars required")
expect_failure("multi-component without a component",
               image((5, 5, 5), np.arange(375, dtype=np.float32), components=3),
               "has 3 components; choose one with the component option")
expect_failure("1-wide axis", image((8, 8, 1), np.arange(64, dtype=np.float32)),
               "at least 2 samples on every axis")

# pvbatch keeps running, and the plugin still works after the failure.
again, fd_again = compare_with_cli("sphere after a failure", sphere, sphere_vti, 8, 0.01)
Delete(again)

# ---- An unstructured grid is refused by the input domain ------------------------
unstructured = Clip(Input=wavelet)
unstructured.UpdatePipeline()
probe = HybridOctree(Input=wavelet)
domain = probe.GetProperty("Input").SMProperty.GetDomain("input_type")
check(domain.IsInDomain(wavelet.SMProxy, 0) == 1, "the input domain accepts image data")
check(domain.IsInDomain(unstructured.SMProxy, 0) == 0, "the input domain refuses an unstructured grid")
Delete(probe)

finish()
