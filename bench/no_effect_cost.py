#!/usr/bin/env python3
"""What the effects cost a frame that uses none of them: the CLI's `render` of
one plain composite scene (no shading, Composite, no surface), timed with the
CLI of the commit before the effects work began (eba8085) and with the
current one, alternately.

    python3 bench/no_effect_cost.py [--repeats 15] [--old-commit eba8085]
        [--current build/cargo/release/hybrid-octree] [--json]
        [-- render arguments, default: --dataset shepp-logan --size 128 --width 512 --height 512]

The old CLI is built once from a `git worktree add` of --old-commit in a
temporary folder (`cargo build --release --locked --bin hybrid-octree`), with
its own CARGO_TARGET_DIR under --cache (default ~/.cache/hybrid-octree-bench),
where the binary is kept for the next run; the worktree is removed after.
The current CLI is --current, or built from this checkout
(CARGO_TARGET_DIR, default build/cargo).

Each repetition runs both binaries (which goes first alternates) with
`render --json`; the time is the rendering part the command reports (select
+ SlabPolygons + DrawList + upload + composite, ms), not the process start,
the data generation or the octree build. Printed: the median of each, the
ratio current / old (goal: at most 1.02) and the medians of the compositing
alone.
"""
import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
RENDER_PARTS = ("select_ms", "slab_polygons_ms", "drawlist_ms", "upload_ms", "composite_ms")
DEFAULT_SCENE = ["--dataset", "shepp-logan", "--size", "128", "--width", "512", "--height", "512"]


def say(text):
    print(text, file=sys.stderr, flush=True)


def build_old(commit, cache):
    """The CLI of `commit`, built once and kept in `cache`; its path."""
    sha = subprocess.run(["git", "-C", REPO, "rev-parse", "--verify", commit + "^{commit}"], check=True,
                         capture_output=True, text=True).stdout.strip()
    binary = os.path.join(cache, "hybrid-octree-" + sha[:12])
    if os.path.exists(binary):
        return binary
    os.makedirs(cache, exist_ok=True)
    checkout = tempfile.mkdtemp(prefix="ho-old-cli-")
    tree = os.path.join(checkout, "src")
    subprocess.run(["git", "-C", REPO, "worktree", "add", "--detach", tree, sha], check=True,
                   capture_output=True)
    try:
        say("building the CLI of %s (once; kept in %s)" % (sha[:12], cache))
        env = dict(os.environ, CARGO_TARGET_DIR=os.path.join(cache, "target-" + sha[:12]))
        subprocess.run(["cargo", "build", "--release", "--locked", "--bin", "hybrid-octree"], cwd=tree,
                       env=env, check=True)
        shutil.copy2(os.path.join(env["CARGO_TARGET_DIR"], "release", "hybrid-octree"), binary)
    finally:
        subprocess.run(["git", "-C", REPO, "worktree", "remove", "--force", tree], check=False)
        shutil.rmtree(checkout, ignore_errors=True)
    return binary


def build_current():
    env = dict(os.environ)
    env.setdefault("CARGO_TARGET_DIR", os.path.join(REPO, "build", "cargo"))
    say("building the current CLI")
    subprocess.run(["cargo", "build", "--release", "--bin", "hybrid-octree"], cwd=REPO, env=env, check=True)
    return os.path.join(env["CARGO_TARGET_DIR"], "release", "hybrid-octree")


def render(binary, scene, png):
    """One `render --json` of the scene: (rendering ms, compositing ms, plan)."""
    out = subprocess.run([binary, "render", "--json", "--output", png] + scene, check=True,
                         capture_output=True, text=True).stdout
    r = json.loads(out)
    return sum(r[k] for k in RENDER_PARTS), r["composite_ms"], r["passes"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeats", type=int, default=15, help="renders per binary")
    parser.add_argument("--old-commit", default="eba8085")
    parser.add_argument("--current", help="the current CLI (default: built from this checkout)")
    parser.add_argument("--cache", default=os.path.join(os.path.expanduser("~"), ".cache", "hybrid-octree-bench"))
    parser.add_argument("--json", action="store_true", help="one JSON object instead of text")
    parser.add_argument("scene", nargs="*", help="render arguments after --")
    args = parser.parse_args()
    if args.repeats < 1:
        parser.error("--repeats must be at least 1")
    scene = args.scene or DEFAULT_SCENE
    if any(a in ("--shade", "--isovalue", "--blend") for a in scene):
        parser.error("the scene must use no effect: drop --shade, --blend and --isovalue")
    binaries = {"old": build_old(args.old_commit, args.cache), "current": args.current or build_current()}
    times = {k: [] for k in binaries}
    composites = {k: [] for k in binaries}
    plans = {}
    with tempfile.TemporaryDirectory(prefix="no-effect-cost-") as tmp:
        png = os.path.join(tmp, "frame.png")
        for k in binaries:  # untimed: page cache, CPU frequency
            render(binaries[k], scene, png)
        for i in range(args.repeats):
            for k in (("old", "current") if i % 2 == 0 else ("current", "old")):
                ms, composite, plans[k] = render(binaries[k], scene, png)
                times[k].append(ms)
                composites[k].append(composite)
    result = {
        "scene": scene,
        "old_commit": args.old_commit,
        "repeats": args.repeats,
        "old_ms": statistics.median(times["old"]),
        "current_ms": statistics.median(times["current"]),
        "old_composite_ms": statistics.median(composites["old"]),
        "current_composite_ms": statistics.median(composites["current"]),
        "old_passes": plans["old"],
        "current_passes": plans["current"],
        "old_all_ms": times["old"],
        "current_all_ms": times["current"],
    }
    result["ratio"] = result["current_ms"] / result["old_ms"]
    result["composite_ratio"] = result["current_composite_ms"] / result["old_composite_ms"]
    if args.json:
        print(json.dumps(result))
        return
    print("render %s, %d repetitions each, alternating; ms of the rendering part (select to composite)"
          % (" ".join(scene), args.repeats))
    print("| CLI | median ms | composite ms | plan |")
    print("|---|---:|---:|---|")
    print("| %s (old) | %.1f | %.1f | %s |" % (args.old_commit, result["old_ms"], result["old_composite_ms"],
                                              " -> ".join(plans["old"])))
    print("| current | %.1f | %.1f | %s |" % (result["current_ms"], result["current_composite_ms"],
                                            " -> ".join(plans["current"])))
    print("current / old: %.3f (compositing alone %.3f); goal <= 1.02"
          % (result["ratio"], result["composite_ratio"]))


if __name__ == "__main__":
    main()
