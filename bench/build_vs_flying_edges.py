"""Volume Octree build (all nodal errors) against vtkFlyingEdges3D and a plain
copy of the volume, side by side in ONE pvpython process, on the same volume
(a built-in dataset: the Shepp-Logan phantom, or `--dataset wavelet`, VTK's
Wavelet, detail everywhere).

    pvpython bench/build_vs_flying_edges.py --plugin build/lib/.../HybridOctree.so \
        --cli build/cargo/release/hybrid-octree [--dataset wavelet] [--sizes 128,256] [--types f32,u8] [--repeats 5]

Both sides get every core: VTK's SMP backend is switched to STDThread with the
thread limit at the core count (pvpython starts it on one thread), and rayon
uses all cores for ours. FlyingEdges runs without normals (its fastest mode) at
an isovalue through the skull/brain boundary. Quotes medians and the ratio
octree build / FlyingEdges from this one run; runs move by 15-25 %.
"""
import argparse
import os
import statistics
import sys
import tempfile

from paraview.simple import LoadPlugin, TrivialProducer
from side_by_side import generated_image, median_ms, time_flying_edges, use_all_cores
from vtkmodules.vtkCommonCore import vtkSMPTools


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--plugin", required=True)
    ap.add_argument("--cli", required=True)
    ap.add_argument("--sizes", default="128,256")
    ap.add_argument("--types", default="f32,u8")
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--leaf-size", type=int, default=16)
    ap.add_argument("--dataset", default="shepp-logan")
    args = ap.parse_args()

    cores = use_all_cores()
    LoadPlugin(args.plugin, remote=False, ns=globals())

    print(f"cores: {cores}, VTK SMP backend {vtkSMPTools.GetBackend()} "
          f"({vtkSMPTools.GetEstimatedNumberOfThreads()} threads), repeats {args.repeats}, medians")
    header = (f"{'size':>5} {'type':>4} {'octree ms':>10} {'filter ms':>10} {'FE ms':>8} {'FE tris':>9} "
              f"{'octree/FE':>10} {'copy ms':>8} {'octree/copy':>12}")
    print(header)
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for size in [int(s) for s in args.sizes.split(",")]:
            for scalar in args.types.split(","):
                path = os.path.join(tmp, f"sl{size}{scalar}.vti")
                image = generated_image(args.cli, args.dataset, size, scalar, path)
                lo, hi = image.GetPointData().GetScalars().GetRange()
                iso = lo + 0.5 * (hi - lo)

                fe_ms, fe = time_flying_edges(image, iso, args.repeats)
                tris = fe.GetOutput().GetNumberOfCells()
                scalars = image.GetPointData().GetScalars()
                copy = scalars.NewInstance()

                def run_copy():
                    copy.DeepCopy(scalars)
                copy_ms = median_ms(run_copy, args.repeats)

                producer = TrivialProducer()
                producer.GetClientSideObject().SetOutput(image)
                # An isovalue above the data range: no surface, so the filter's time is
                # the octree build and its boxes (the surface has its own benchmark).
                octree = HybridOctree(Input=producer, LeafSize=args.leaf_size,  # noqa: F821 (from LoadPlugin)
                                      Isovalue=hi + 1.0, MeasureSurfaceDistance=0)
                octree.UpdatePipeline()
                # Time the VTK filter itself, as FlyingEdges is timed: ParaView's proxy
                # update adds its own data-information pass over the input image.
                algorithm = octree.GetClientSideObject()
                build_ms = []

                def run_octree():
                    # forces a rebuild: the filter caches its octree by the array's MTime
                    image.GetPointData().GetScalars().Modified()
                    algorithm.Update()
                    out = algorithm.GetOutputDataObject(0)
                    build_ms.append(out.GetFieldData().GetArray("build_ms").GetValue(0))
                filter_ms = median_ms(run_octree, args.repeats)
                oct_ms = statistics.median(build_ms[1:])
                assert len(set(build_ms)) > 1, "the filter did not rebuild between repeats"
                ratio = oct_ms / fe_ms
                rows.append(ratio)
                print(f"{size:>5} {scalar:>4} {oct_ms:>10.1f} {filter_ms:>10.1f} {fe_ms:>8.1f} {tris:>9} {ratio:>10.2f} "
                      f"{copy_ms:>8.1f} {oct_ms / copy_ms:>12.2f}")
    print("octree ms: Rust build of the Volume Octree with every nodal error (field data build_ms);")
    print("filter ms: the whole vtkHybridOctreeFilter::Update() (bridge + build + boxes polydata);")
    print("FE ms: vtkFlyingEdges3D, one isosurface at the mid-range isovalue, no normals;")
    print("copy ms: vtkDataArray::DeepCopy of the point scalars (one read and one write of the volume).")
    return 0


if __name__ == "__main__":
    sys.exit(main())
