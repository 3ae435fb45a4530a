"""Hybrid Octree isosurface (DiscMC + coplanar face compression, and the
interpolated Marching Cubes mode) against vtkFlyingEdges3D, side by side in
ONE pvpython process, on the same volume at the same isovalue.

    pvpython bench/surface_vs_flying_edges.py --plugin build/lib/.../HybridOctree.so \
        --cli build/cargo/release/hybrid-octree [--cases shepp-logan:256:0.5,...] \
        [--repeats 9] [--no-distance]

Our side comes from the ParaView filter `HybridOctree` (loaded with LoadPlugin)
in this process: output port 1 is the surface at `Isovalue` in `SurfaceMode`
0 (discretized) or 1 (interpolated), with `MeasureSurfaceDistance` off while
timing. Its time is the field data `extract_ms + compress_ms`, measured inside
the Rust core; each run marks the input array modified, so the filter
rebuilds the Volume Octree and extracts the surface again (the octree build is
shown in its own column, `build ms`: it is paid once per volume, not per
isovalue). The CLI only writes the datasets.

FlyingEdges: vtkFlyingEdges3D without normals (its fastest mode, the goal's
baseline) and with normals (what ours computes too). Both sides get every
core: VTK's SMP backend is switched to STDThread with the thread limit at the
core count (pvpython starts it on one thread), rayon uses all cores for ours.
Timing is interleaved: each round runs all four once (FE, FE with normals,
ours discretized, ours interpolated), so that the machine's slow spells hit
them alike; the ratio column is the median of the per-round ratios.

Triangles: our output cells are triangles (each merged face triangulated
with its own vertices); FlyingEdges outputs triangles.

Distance to the FlyingEdges surface, in voxel units (both surfaces mapped to
index space, (x - origin) / spacing): samples of our surface are every point
and the vertex centroid of every polygon, each measured to the FE triangles
with a vtkStaticCellLocator (FindClosestPoint); samples of the FE surface are
every FE point, measured to our surface triangulated with vtkTriangleFilter.
Reported: mean and max over the samples of both directions (a sampled
symmetric Hausdorff distance; the max is a lower bound of the true one).

Goals, checked on the discretized rows:
  (a) DiscMC extract + compress time <= FlyingEdges time (same threads);
  (b) DiscMC triangles <= 0.5 x FlyingEdges triangles;
  (c) max distance to the FlyingEdges surface <= half a voxel diagonal (0.866).
"""
import argparse
import os
import statistics
import sys
import tempfile

import numpy as np
from paraview.simple import Delete, LoadPlugin, TrivialProducer
import time

from side_by_side import generated_image, use_all_cores
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import reference, vtkPoints, vtkSMPTools
from vtkmodules.vtkCommonDataModel import vtkGenericCell, vtkPolyData, vtkStaticCellLocator, vtkStaticPointLocator
from vtkmodules.vtkFiltersCore import vtkFlyingEdges3D, vtkTriangleFilter

HALF_DIAGONAL = 0.5 * 3 ** 0.5
DEFAULT_CASES = "shepp-logan:256:0.5,shepp-logan:256:0.25,marschner-lobb:256:0.5,marschner-lobb:256:0.3"


def field(data, name):
    a = data.GetFieldData().GetArray(name)
    if a is None:
        a = data.GetFieldData().GetAbstractArray(name)
    return a.GetValue(0)


def in_index_space(poly, origin, spacing):
    """A copy of `poly` whose points are (x - origin) / spacing, as doubles."""
    pts = vtk_to_numpy(poly.GetPoints().GetData()).astype(np.float64)
    pts = (pts - np.asarray(origin)) / np.asarray(spacing)
    out = vtkPolyData()
    out.ShallowCopy(poly)
    points = vtkPoints()
    points.SetData(numpy_to_vtk(np.ascontiguousarray(pts), deep=True))
    out.SetPoints(points)
    return out, pts


def polygon_stats(poly):
    """(polygons, fan triangles, vertex centroids) of the polygons of `poly`."""
    cells = poly.GetPolys()
    offsets = vtk_to_numpy(cells.GetOffsetsArray()).astype(np.int64)
    conn = vtk_to_numpy(cells.GetConnectivityArray()).astype(np.int64)
    counts = np.diff(offsets)
    pts = vtk_to_numpy(poly.GetPoints().GetData()).astype(np.float64)
    if len(counts) == 0:
        return 0, 0, np.zeros((0, 3))
    centroids = np.add.reduceat(pts[conn], offsets[:-1], axis=0) / counts[:, None]
    return len(counts), int((counts - 2).sum()), centroids


def distances_to(samples, surface):
    """Distance from each row of `samples` to the nearest triangle of `surface`."""
    locator = vtkStaticCellLocator()
    locator.SetDataSet(surface)
    locator.BuildLocator()
    closest = [0.0, 0.0, 0.0]
    cell = vtkGenericCell()
    cell_id, sub_id, dist2 = reference(0), reference(0), reference(0.0)
    out = np.empty(len(samples))
    for i, p in enumerate(samples.tolist()):
        locator.FindClosestPoint(p, closest, cell, cell_id, sub_id, dist2)
        out[i] = dist2.get()
    return np.sqrt(out)


def surface_distance(ours, fe, origin, spacing):
    """Symmetric sampled distance (mean, max, samples) in voxels between our
    surface and the FlyingEdges surface."""
    ours_idx, ours_pts = in_index_space(ours, origin, spacing)
    fe_idx, fe_pts = in_index_space(fe, origin, spacing)
    _, _, centroids = polygon_stats(ours_idx)
    tri = vtkTriangleFilter()
    tri.SetInputData(ours_idx)
    tri.Update()
    d1 = distances_to(np.vstack([ours_pts, centroids]), fe_idx)
    d2 = distances_to(fe_pts, tri.GetOutput())
    d = np.concatenate([d1, d2])
    return float(d.mean()), float(d.max()), len(d)


def vertex_offset(ours, fe, origin, spacing):
    """Max distance (voxels) from each of our points to the nearest FlyingEdges point."""
    _, ours_pts = in_index_space(ours, origin, spacing)
    fe_idx, fe_pts = in_index_space(fe, origin, spacing)
    locator = vtkStaticPointLocator()
    locator.SetDataSet(fe_idx)
    locator.BuildLocator()
    nearest = np.fromiter((locator.FindClosestPoint(p) for p in ours_pts.tolist()), np.int64, len(ours_pts))
    return float(np.linalg.norm(fe_pts[nearest] - ours_pts, axis=1).max()) if len(ours_pts) else 0.0


class FilterSide:
    """Our surface in one mode, from the HybridOctree filter in this process."""

    def __init__(self, image, iso, mode):
        self.image, self.mode = image, mode
        self.producer = TrivialProducer()
        self.producer.GetClientSideObject().SetOutput(image)
        self.proxy = HybridOctree(Input=self.producer, Isovalue=iso,  # noqa: F821 (from LoadPlugin)
                                  SurfaceMode=0 if mode == "discretized" else 1, MeasureSurfaceDistance=0)
        self.proxy.UpdatePipeline()
        self.algorithm = self.proxy.GetClientSideObject()
        self.samples = []

    def once(self):
        """One rebuild + extraction; records (extract ms, compress ms, build ms)."""
        # forces a rebuild and a new extraction: the filter caches both by the array's MTime
        self.image.GetPointData().GetScalars().Modified()
        self.algorithm.Update()
        s = self.algorithm.GetOutputDataObject(1)
        b = self.algorithm.GetOutputDataObject(0)
        self.samples.append((field(s, "extract_ms"), field(s, "compress_ms"), field(b, "build_ms")))
        return self.samples[-1][0] + self.samples[-1][1]

    def surface(self):
        """(surface polydata, field data dict) of the last run."""
        surface = vtkPolyData()
        surface.DeepCopy(self.algorithm.GetOutputDataObject(1))
        assert field(surface, "surface_mode") == self.mode, field(surface, "surface_mode")
        info = {k: field(surface, k) for k in ("polygons", "faces", "triangles", "uncompressed_triangles")}
        return surface, info

    def close(self):
        Delete(self.proxy)
        Delete(self.producer)


def flying_edges(image, isovalue, normals):
    fe = vtkFlyingEdges3D()
    fe.SetInputData(image)
    fe.SetValue(0, isovalue)
    fe.SetComputeNormals(normals)
    return fe


def wall_ms(fn):
    t = time.perf_counter()
    fn()
    return (time.perf_counter() - t) * 1e3


def rounds(image, iso, repeats):
    """Interleaved timing: each round runs FlyingEdges (without and with
    normals) and our two modes once each, so that a slow spell of the machine
    hits all of them alike; round 0 is a warm-up. Returns the FE filter
    without normals, per-series times and the two sides."""
    fe, fe_n = flying_edges(image, iso, False), flying_edges(image, iso, True)
    sides = {m: FilterSide(image, iso, m) for m in ("discretized", "interpolated")}
    times = {"fe": [], "fe_normals": [], "discretized": [], "interpolated": []}

    def run_fe(f):
        f.Modified()
        f.Update()
    for r in range(repeats + 1):
        t = {"fe": wall_ms(lambda: run_fe(fe)), "fe_normals": wall_ms(lambda: run_fe(fe_n))}
        for m, side in sides.items():
            t[m] = side.once()
        if r > 0:
            for k, v in t.items():
                times[k].append(v)
    for side in sides.values():
        side.samples = side.samples[1:]
        assert len(set(side.samples)) > 1, "the filter did not extract again between repeats"
    return fe, times, sides


def timing(samples):
    """Medians of (extract + compress, extract, compress, build) over `samples`."""
    total = statistics.median(e + c for e, c, _ in samples)
    return (total, statistics.median(e for e, _, _ in samples),
            statistics.median(c for _, c, _ in samples), statistics.median(b for _, _, b in samples))


def filter_has_surface():
    """Whether the loaded HybridOctree filter has the surface output (its prototype, no instance)."""
    from paraview import servermanager
    proto = servermanager.vtkSMProxyManager.GetProxyManager().GetActiveSessionProxyManager() \
        .GetPrototypeProxy("filters", "HybridOctree")
    return all(proto.GetProperty(n) is not None for n in ("Isovalue", "SurfaceMode", "MeasureSurfaceDistance")) \
        and proto.GetNumberOfOutputPorts() >= 2


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--plugin", required=True)
    ap.add_argument("--cli", required=True)
    ap.add_argument("--cases", default=DEFAULT_CASES, help="dataset:size:isovalue,...")
    ap.add_argument("--repeats", type=int, default=9)
    ap.add_argument("--no-distance", action="store_true", help="skip the distance measurement")
    args = ap.parse_args()

    cores = use_all_cores()
    LoadPlugin(args.plugin, remote=False, ns=globals())
    if not filter_has_surface():
        sys.exit("the loaded HybridOctree filter has no surface output (Isovalue/SurfaceMode/port 1)")

    print(f"cores: {cores}, VTK SMP backend {vtkSMPTools.GetBackend()} "
          f"({vtkSMPTools.GetEstimatedNumberOfThreads()} threads), rayon all cores, "
          f"{args.repeats} interleaved rounds (medians)")
    print()
    cols = ("dataset", "size", "iso", "mode", "ours ms", "extract", "compress", "build ms", "faces",
            "triangles", "FE ms", "FE+n ms", "FE tris", "time/FE", "t/FE+n", "tris/FE", "dist mean", "dist max")
    widths = (14, 4, 5, 12, 8, 8, 8, 8, 8, 9, 7, 7, 9, 7, 7, 7, 9, 8)
    line = " ".join(f"{c:>{w}}" if i > 0 else f"{c:<{w}}" for i, (c, w) in enumerate(zip(cols, widths)))
    print(line)
    print("-" * len(line))
    results = []
    images = {}
    with tempfile.TemporaryDirectory() as tmp:
        for case in args.cases.split(","):
            dataset, size, iso = case.split(":")
            size, iso = int(size), float(iso)
            path = os.path.join(tmp, f"{dataset}{size}.vti")
            if (dataset, size) not in images:  # one volume for all isovalues of a dataset
                images[(dataset, size)] = generated_image(args.cli, dataset, size, "f32", path)
            image = images[(dataset, size)]
            origin, spacing = image.GetOrigin(), image.GetSpacing()

            fe, times, sides = rounds(image, iso, args.repeats)
            fe_out = vtkPolyData()
            fe_out.DeepCopy(fe.GetOutput())
            fe_tris = fe_out.GetNumberOfCells()
            fe_ms, fe_n_ms = statistics.median(times["fe"]), statistics.median(times["fe_normals"])
            for mode, side in sides.items():
                ms, ex, co, build = timing(side.samples)
                surface, info = side.surface()
                polys, tris, _ = polygon_stats(surface)
                assert (polys, tris) == (int(info["polygons"]), int(info["triangles"])), (polys, tris, info)
                # Per-round ratios, then their median: robust to the machine's slow spells.
                ratio = statistics.median(o / f for o, f in zip(times[mode], times["fe"]))
                ratio_n = statistics.median(o / f for o, f in zip(times[mode], times["fe_normals"]))
                if args.no_distance:
                    dmean = dmax = float("nan")
                else:
                    dmean, dmax, _ = surface_distance(surface, fe_out, origin, spacing)
                vmax = vertex_offset(surface, fe_out, origin, spacing) \
                    if mode == "interpolated" and not args.no_distance else float("nan")
                r = dict(dataset=dataset, size=size, iso=iso, mode=mode, ms=ms, extract=ex, compress=co,
                         build=build, faces=int(info["faces"]), polygons=polys, triangles=tris, fe_ms=fe_ms,
                         fe_n_ms=fe_n_ms, fe_tris=fe_tris, time_ratio=ratio, time_ratio_n=ratio_n,
                         tri_ratio=tris / fe_tris, dmean=dmean, dmax=dmax,
                         uncompressed=int(info["uncompressed_triangles"]), points=surface.GetNumberOfPoints(),
                         fe_points=fe_out.GetNumberOfPoints(), vmax=vmax)
                results.append(r)
                vals = (dataset, size, f"{iso:g}", mode, f"{ms:.1f}", f"{ex:.1f}", f"{co:.1f}", f"{build:.1f}",
                        r["faces"], tris, f"{fe_ms:.1f}", f"{fe_n_ms:.1f}", fe_tris, f"{ratio:.2f}",
                        f"{ratio_n:.2f}", f"{r['tri_ratio']:.2f}", f"{dmean:.4f}", f"{dmax:.4f}")
                print(" ".join(f"{v:>{w}}" if i > 0 else f"{v:<{w}}" for i, (v, w) in enumerate(zip(vals, widths))),
                      flush=True)
                side.close()

    print()
    print("ours ms = extract + compress (ms, median): per node, marching and merging coplanar facets;")
    print("  then vertex naming, triangulation of the faces, points, normals and assembly; both timed inside")
    print("  the Rust core. build ms = Volume Octree build (paid once per volume, not in 'ours ms').")
    print("  faces = merged coplanar faces; triangles = our output cells (the faces triangulated).")
    print("  FE ms / FE+n ms = vtkFlyingEdges3D at the same isovalue without / with normals (ours always")
    print("  computes normals), median; time/FE and t/FE+n = median over the rounds of ours / FlyingEdges;")
    print("  tris/FE = triangles / FE triangles; dist mean / max = sampled symmetric distance between our")
    print("  surface and the FlyingEdges surface, in voxels.")
    print()
    print("goals on the discretized rows:")
    disc = [r for r in results if r["mode"] == "discretized"]
    goals = (
        ("(a) extract+compress time <= FlyingEdges time (without normals; median of per-round ratios)",
         lambda r: r["time_ratio"] <= 1.0,
         lambda r: f"{r['ms']:.1f} vs {r['fe_ms']:.1f} ms, ratio {r['time_ratio']:.2f}x "
                   f"({r['time_ratio_n']:.2f}x FE with normals)"),
        ("(b) triangles <= 0.5 x FlyingEdges triangles", lambda r: r["triangles"] <= 0.5 * r["fe_tris"],
         lambda r: f"{r['triangles']} vs {r['fe_tris']} ({r['tri_ratio']:.2f}x)"),
        (f"(c) max distance to FE surface <= {HALF_DIAGONAL:.3f} voxel", lambda r: r["dmax"] <= HALF_DIAGONAL,
         lambda r: f"max {r['dmax']:.4f}, mean {r['dmean']:.4f}"),
    )
    for title, ok, show in goals:
        print(f"  {title}:")
        for r in disc:
            verdict = "PASS" if ok(r) else "MISS"
            print(f"    {verdict}  {r['dataset']} {r['size']} iso {r['iso']:g}: {show(r)}")
    print()
    print("interpolated rows (classic MC through the octree) against FlyingEdges:")
    for r in results:
        if r["mode"] == "interpolated":
            print(f"  {r['dataset']} {r['size']} iso {r['iso']:g}: {r['ms']:.1f} ms ({r['time_ratio']:.2f}x FE), "
                  f"{r['triangles']} triangles ({r['tri_ratio']:.3f}x FE), distance mean {r['dmean']:.2e}, "
                  f"max {r['dmax']:.2e} voxel; {r['points']} points vs FE {r['fe_points']}, each within "
                  f"{r['vmax']:.1e} voxel of an FE point")
    print("  (same points as FlyingEdges; a nonzero surface distance is where the two case tables cut a cell")
    print("  into different triangles: FE's classic table vs our face-rule table, e.g. other quad diagonals)")
    print("compression on the discretized rows (uncompressed DiscMC triangles -> triangles after merging):")
    for r in disc:
        print(f"  {r['dataset']} {r['size']} iso {r['iso']:g}: {r['uncompressed']} -> {r['triangles']} "
              f"({r['triangles'] / r['uncompressed']:.2f}x), in {r['faces']} merged faces")
    return 0


if __name__ == "__main__":
    sys.exit(main())
