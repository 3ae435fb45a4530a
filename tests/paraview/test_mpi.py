"""The representation on 1 and 2 MPI ranks draws the same picture.

    pvpython test_mpi.py --plugin <HybridOctree.so> --cli <hybrid-octree> --workdir <dir>

Runs `mpiexec -n 1 pvbatch mpi_scene.py` and `mpiexec -n 2 pvbatch
mpi_scene.py` on a 96^3 Shepp-Logan phantom, the volume alone and with a
translucent isosurface, and checks:

- the 2-rank run had 2 ranks, and rank 0 held only part of the data: its
  octree's resident texture bytes are below the 1-rank run's (each rank
  builds and draws its own piece);
- the two pictures agree, RGB RMSE (in [0, 1]) at most 0.01 for the volume
  alone: each rank's 8-bit image is composited by ParaView (IceT) in
  visibility order, a rounding per rank, and each rank's transfer-function
  table spans its own piece's value range;
- with the isosurface at most 0.03: each rank extracts the surface of its
  own piece, so along the piece boundary the vertex normals average only
  one piece's triangles and merged coplanar faces cut by the boundary are
  triangulated apart (the shading of those triangles differs).
"""
import argparse
import json
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from pvtest import Checks, generate_phantom, read_png_rgb, report, rmse  # noqa: E402

parser = argparse.ArgumentParser()
parser.add_argument("--plugin", required=True)
parser.add_argument("--cli", required=True)
parser.add_argument("--workdir", required=True)
parser.add_argument("--mpiexec", default="mpiexec")
parser.add_argument("--pvbatch", default="pvbatch")
args = parser.parse_args()
os.makedirs(args.workdir, exist_ok=True)
t = Checks("HybridOctree MPI test")

data = generate_phantom(args.cli, args.workdir, 96)
scene = os.path.join(os.path.dirname(os.path.abspath(__file__)), "mpi_scene.py")
mpiexec = shutil.which(args.mpiexec) or args.mpiexec
# pvpython runs as an MPI singleton: its OMPI_/PMIX_ variables would make
# mpiexec's ranks join it instead of starting their own job.
env = {k: v for k, v in os.environ.items() if not k.startswith(("OMPI_", "PMIX_", "OPAL_"))}
# Open MPI in containers: no cross-memory attach between ranks.
env.setdefault("OMPI_MCA_btl_vader_single_copy_mechanism", "none")


def run(ranks, surface_opacity):
    name = "ranks%d-surface%g" % (ranks, surface_opacity)
    image = os.path.join(args.workdir, name + ".png")
    stats = os.path.join(args.workdir, name + ".json")
    command = [mpiexec, "-n", str(ranks), "--oversubscribe"]
    if os.geteuid() == 0:
        command.append("--allow-run-as-root")
    command += [args.pvbatch, scene, "--plugin", args.plugin, "--data", data, "--image", image, "--json", stats,
                "--surface-opacity", str(surface_opacity)]
    done = subprocess.run(command, env=env, capture_output=True, text=True, timeout=600)
    report("mpiexec -n %d (surface opacity %g): rc %d" % (ranks, surface_opacity, done.returncode))
    if done.returncode != 0:
        report(done.stdout[-3000:] + done.stderr[-3000:])
        t.check(False, "mpiexec -n %d pvbatch mpi_scene.py failed" % ranks)
        t.finish()
    with open(stats) as f:
        return read_png_rgb(image), json.load(f)


# (surface opacity, plan, RMSE threshold)
SCENES = [(0.0, "volume", 0.01), (0.5, "surface-in-slabs,volume", 0.03)]
for surface_opacity, plan, threshold in SCENES:
    one, stats1 = run(1, surface_opacity)
    two, stats2 = run(2, surface_opacity)
    report("1 rank: %s" % stats1)
    report("2 ranks: %s" % stats2)
    t.check(stats1["ranks"] == 1 and stats2["ranks"] == 2, "ranks: %s and %s" % (stats1["ranks"], stats2["ranks"]))
    # The two pieces share the plane of points on their common face.
    t.check(stats1["points"] == 96 ** 3 and 96 ** 3 <= stats2["points"] <= 96 ** 3 + 96 ** 2,
            "the whole volume is read: %d and %d points" % (stats1["points"], stats2["points"]))
    t.check(stats1["LastPlan"] == stats2["LastPlan"] == plan,
            "plans: %r, %r (expected %r)" % (stats1["LastPlan"], stats2["LastPlan"], plan))
    t.check(0.0 < stats2["LastTextureMB"] < stats1["LastTextureMB"],
            "rank 0 of 2 draws only its piece: %.3f MB against %.3f MB on one rank"
            % (stats2["LastTextureMB"], stats1["LastTextureMB"]))
    corner = one[:1].repeat(one.shape[0], axis=0)
    t.check(rmse(one, corner) > 0.02, "the 1-rank picture shows the volume")
    difference = rmse(one, two)
    report("surface opacity %g: 2 ranks vs 1 rank: RGB RMSE %.4f (threshold %g)"
           % (surface_opacity, difference, threshold))
    t.check(difference <= threshold, "surface opacity %g: 2 ranks vs 1 rank: RMSE %.4f above %g"
            % (surface_opacity, difference, threshold))
t.finish()
