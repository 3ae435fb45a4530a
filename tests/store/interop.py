#!/usr/bin/env python3
"""OME-Zarr interoperability of the `hybrid-octree` CLI with zarr-python and ome-zarr.

1. Stores the CLI did not write open: an NGFF 0.5 / Zarr v3 image (zarr-python's
   default zstd codec), an NGFF 0.4 / Zarr v2 image with time and channel axes
   (its default Blosc compressor) and an image written by
   `ome_zarr.writer.write_image` (its default pyramid). `info` and `build`
   report numpy's dims, type, spacing, origin and value range (of t = 0,
   c = 0), and `render` draws the same PNG bytes as the same samples read as
   a raw file with the same spacing and origin.
2. A store `convert` writes opens in zarr-python: level p is numpy's
   `a[min(i 2^p, n - 1)]` per axis of level 0, the metadata validates as
   NGFF 0.5 (ome-zarr-models), and the `hybrid_octree` group holds its arrays.
3. Hostile stores (a truncated chunk, a path out of the store, a 2D image,
   complex and int64 samples, declared shapes that overflow or exceed memory,
   chunks too small to list) give exit status 2 and one `error:` line under
   an address-space cap: never a signal, a panic or a hang.

usage: interop.py HYBRID_OCTREE_BINARY [--keep DIR]
"""

import json
import os
import re
import shutil
import sys

import numpy as np
import ome_zarr
import ome_zarr.writer
import ome_zarr_models
import zarr
from ome_zarr_models.v05 import Image as ImageV05

from cli_harness import WORK, check, finish, path, run, run_ok


# ------------------------------------------------------------------ volumes


def phantom(shape, seed):
    """A real-looking volume (z, y, x) in [0, 1]: a few soft blobs, a tube and noise."""
    rng = np.random.default_rng(seed)
    z, y, x = np.meshgrid(*[np.linspace(-1, 1, n) for n in shape], indexing="ij")
    v = np.zeros(shape)
    for _ in range(4):
        c = rng.uniform(-0.6, 0.6, 3)
        r = rng.uniform(0.15, 0.4)
        v += np.exp(-((z - c[0]) ** 2 + (y - c[1]) ** 2 + (x - c[2]) ** 2) / (r * r))
    v += 0.8 * np.exp(-((y - 0.3 * z) ** 2 + (x + 0.2) ** 2) / 0.01)
    v += 0.05 * rng.standard_normal(shape)
    v -= v.min()
    return v / v.max()


def ngff_axes(names):
    kinds = {"t": "time", "c": "channel"}
    return [{"name": n, "type": kinds.get(n, "space"), **({"unit": "micrometer"} if n in "zyx" else {})}
            for n in names]


def multiscale(names, scale, translation, version):
    """`multiscales` with one dataset '0' (the others are not read by the CLI)."""
    ms = {"axes": ngff_axes(names), "name": "phantom",
          "datasets": [{"path": "0", "coordinateTransformations": [
              {"type": "scale", "scale": scale}, {"type": "translation", "translation": translation}]}]}
    if version == "0.4":
        ms["version"] = "0.4"
    return [ms]


def write_v3(name, a, spacing_zyx, origin_zyx):
    """NGFF 0.5 / Zarr v3 with zarr-python's default codecs (bytes + zstd) and a second, coarser level."""
    g = zarr.open_group(path(name), mode="w", zarr_format=3)
    g.create_array("0", data=a, chunks=(8, 8, 8), dimension_names=["z", "y", "x"])
    g.create_array("1", data=a[::2, ::2, ::2], chunks=(8, 8, 8), dimension_names=["z", "y", "x"])
    ms = multiscale("zyx", list(spacing_zyx), list(origin_zyx), "0.5")
    ms[0]["datasets"].append({"path": "1", "coordinateTransformations": [
        {"type": "scale", "scale": [2 * s for s in spacing_zyx]}, {"type": "translation", "translation": list(origin_zyx)}]})
    g.attrs["ome"] = {"version": "0.5", "multiscales": ms}
    return path(name)


def write_v2_5d(name, a5, spacing_zyx, origin_zyx):
    """NGFF 0.4 / Zarr v2 (t, c, z, y, x) with zarr-python's default compressor (Blosc)."""
    g = zarr.open_group(path(name), mode="w", zarr_format=2)
    g.create_array("0", data=a5, chunks=(1, 1, 8, 8, 8))
    g.attrs["multiscales"] = multiscale("tczyx", [1.0, 1.0, *spacing_zyx], [0.0, 0.0, *origin_zyx], "0.4")
    return path(name)


def write_ome_zarr(name, a, spacing_zyx):
    """`ome_zarr.writer.write_image` with its defaults (latest format, its pyramid and codec)."""
    ome_zarr.writer.write_image(a, path(name), axes="zyx", scale=dict(zip("zyx", spacing_zyx)))
    return path(name)


def raw_args(a, spacing_zyx, origin_zyx):
    """The same samples as a raw file: `--file F --dims X,Y,Z --type T --spacing --origin`."""
    types = {np.uint8: "u8", np.uint16: "u16", np.int16: "i16", np.float32: "f32"}
    raw = path(f"raw-{len(os.listdir(WORK))}.raw")
    np.ascontiguousarray(a).astype(a.dtype.newbyteorder("<")).tofile(raw)
    xyz = lambda v: ",".join(str(float(c)) for c in v[::-1])
    return ["--file", raw, "--dims", ",".join(str(n) for n in a.shape[::-1]), "--type", types[a.dtype.type],
            "--spacing", xyz(spacing_zyx), "--origin", xyz(origin_zyx)]


# ------------------------------------------------------------------ 1. foreign stores


def info_fields(text):
    fields = dict(re.findall(r"^([a-zA-Z ]+):\s+(.*)$", text, re.M))
    dims = [int(n) for n in re.match(r"(\d+) x (\d+) x (\d+)", fields["dims"]).groups()]
    lo, hi = re.match(r"(\S+) \.\. (\S+)", fields["value range"]).groups()
    return dims, fields["type"], json.loads(fields["spacing"]), json.loads(fields["origin"]), float(lo), float(hi)


def check_foreign(label, store, a, spacing_zyx, origin_zyx, type_name, warned=False):
    """`info`, `build` and `render` of `store`, whose level 0 (t = c = 0) is `a` (z, y, x)."""
    out, err = run_ok("info", "--file", store)
    dims, typ, spacing, origin, lo, hi = info_fields(out)
    check(dims == list(a.shape[::-1]), f"{label}: info dims {dims} != {list(a.shape[::-1])}")
    check(typ == type_name, f"{label}: info type {typ} != {type_name}")
    check(np.allclose(spacing, spacing_zyx[::-1], rtol=1e-12), f"{label}: spacing {spacing} != {spacing_zyx[::-1]}")
    check(np.allclose(origin, origin_zyx[::-1], rtol=1e-12), f"{label}: origin {origin} != {origin_zyx[::-1]}")
    check(np.isclose(lo, float(a.min()), rtol=1e-6) and np.isclose(hi, float(a.max()), rtol=1e-6),
          f"{label}: value range {lo} .. {hi} != numpy {a.min()} .. {a.max()}")
    check(("index 0 of each is read" in err) == warned, f"{label}: time/channel warning {warned} expected: {err!r}")
    b = json.loads(run_ok("build", "--file", store, "--leaf-size", "8", "--json")[0])
    raw = raw_args(a, spacing_zyx, origin_zyx)
    r = json.loads(run_ok("build", *raw, "--leaf-size", "8", "--json")[0])
    check(b["dims"] == list(a.shape[::-1]) and b["scalar_type"] == type_name, f"{label}: build {b['dims']} {b['scalar_type']}")
    check(np.isclose(b["value_min"], float(a.min()), rtol=1e-6) and np.isclose(b["value_max"], float(a.max()), rtol=1e-6),
          f"{label}: build value range {b['value_min']} .. {b['value_max']}")
    for key in ["node_count", "cut_count", "value_min", "value_max"]:
        check(b[key] == r[key], f"{label}: build {key} {b[key]} from the store, {r[key]} from raw")
    for budget in ["64", "0.004"]:
        png_store, png_raw = path(f"{label}-{budget}-store.png"), path(f"{label}-{budget}-raw.png")
        # A store written elsewhere is drawn from disk, weighed by screen space alone: the raw volume too.
        common = ["--width", "128", "--height", "96", "--budget-mb", budget, "--azimuth", "30", "--elevation", "20",
                  "--view-selection", "screen", "--json"]
        out, err = run_ok("render", "--file", store, *common, "--output", png_store)
        s = json.loads(out)
        check(err.count("index 0 of each is read") == int(warned), f"{label}: render warned {err!r}")
        q = json.loads(run_ok("render", *raw, *common, "--output", png_raw)[0])
        with open(png_store, "rb") as f1, open(png_raw, "rb") as f2:
            same = f1.read() == f2.read()
        check(same, f"{label}: render at --budget-mb {budget}: the store's PNG differs from the raw volume's")
        check(s["bricks"] == q["bricks"] and s["estimated_error"] == q["estimated_error"] and s["bricks"] > 0,
              f"{label}: render at {budget} MB: bricks {s['bricks']}/{q['bricks']}, error {s['estimated_error']}/{q['estimated_error']}")
    print(f"ok: {label}: {list(a.shape[::-1])} {type_name}, spacing {spacing}, origin {origin}, "
          f"values {lo} .. {hi}, renders equal to raw", flush=True)


# ------------------------------------------------------------------ 2. convert, read by zarr-python


def check_converted(label, store, a, spacing_zyx, origin_zyx):
    """A store `convert` wrote, read by zarr-python; `a` is level 0 (z, y, x) when known."""
    g = zarr.open_group(store, mode="r")
    ome = g.attrs["ome"]
    check(ome["version"] == "0.5", f"{label}: ome.version {ome['version']}")
    try:
        ImageV05.from_zarr(g)
        check(True, "")
    except Exception as e:  # the validator's own message says what is wrong
        check(False, f"{label}: not a valid NGFF 0.5 image (ome-zarr-models): {e}")
    ms = ome["multiscales"][0]
    names = [ax["name"] for ax in ms["axes"]]
    check(names == ["z", "y", "x"] and all(ax["type"] == "space" for ax in ms["axes"]), f"{label}: axes {ms['axes']}")
    meta = g.attrs["hybrid_octree"]
    level0 = g[ms["datasets"][0]["path"]][...]
    if a is not None:
        check(level0.dtype == a.dtype and np.array_equal(level0, a), f"{label}: level 0 differs from the input")
    n = np.array(level0.shape)
    check(meta["dims"] == list(n[::-1]), f"{label}: hybrid_octree dims {meta['dims']}")
    check(meta["levels"] == len(ms["datasets"]), f"{label}: {meta['levels']} levels, {len(ms['datasets'])} datasets")
    check(meta["value_range"] == [float(level0.min()), float(level0.max())], f"{label}: value_range {meta['value_range']}")
    for p, d in enumerate(ms["datasets"]):
        arr = g[d["path"]]
        check(list(arr.metadata.dimension_names) == names, f"{label}: level {p} dimension_names {arr.metadata.dimension_names}")
        m = (n - 1 + (1 << p) - 1) // (1 << p) + 1
        idx = [np.minimum(np.arange(m[k]) * (1 << p), n[k] - 1) for k in range(3)]
        expect = level0[np.ix_(*idx)]
        got = arr[...]
        check(got.shape == expect.shape and np.array_equal(got, expect),
              f"{label}: level {p} ({got.shape}) is not level 0 at min(i 2^{p}, n - 1) ({expect.shape})")
        t = {c["type"]: c for c in d["coordinateTransformations"]}
        check(np.allclose(t["scale"]["scale"], np.array(spacing_zyx) * (1 << p)), f"{label}: level {p} scale {t['scale']}")
        check(np.allclose(t["translation"]["translation"], origin_zyx), f"{label}: level {p} translation {t['translation']}")
    h = g["hybrid_octree"]
    arrays = {k: h[k] for k in ["min", "max", "errors", "squared_errors"]}
    check(arrays["min"].shape == arrays["max"].shape and arrays["min"].dtype == np.float64
          and arrays["errors"].shape == arrays["squared_errors"].shape and arrays["errors"].dtype == np.float32,
          f"{label}: hybrid_octree arrays {[(k, v.shape, v.dtype) for k, v in arrays.items()]}")
    mins, maxs = arrays["min"][...], arrays["max"][...]
    check(np.all(mins <= maxs) and mins.min() == level0.min() and maxs.max() == level0.max(),
          f"{label}: node min/max do not bound the samples")
    check(np.all(arrays["errors"][...] >= 0), f"{label}: negative nodal errors")
    print(f"ok: {label}: {len(ms['datasets'])} levels equal numpy's strides, NGFF 0.5 valid, "
          f"{arrays['min'].shape[0]} nodes", flush=True)


# ------------------------------------------------------------------ 3. hostile stores


def ome_group(name, shape=None, dtype="u1", data=None, names="zyx", dataset_path="0", zarr_format=3, chunks=None):
    g = zarr.open_group(path(name), mode="w", zarr_format=zarr_format)
    if data is not None:
        g.create_array("0", data=data, chunks=chunks or data.shape)
    else:
        g.create_array("0", shape=shape, dtype=dtype, chunks=chunks or shape)
    ms = multiscale(names, [1.0] * len(names), [0.0] * len(names), "0.5")
    ms[0]["datasets"][0]["path"] = dataset_path
    g.attrs["ome"] = {"version": "0.5", "multiscales": ms}
    return path(name)


def hostile_stores(converted):
    cases = {}
    # A Blosc chunk of a zarr-python Zarr v2 store cut in half.
    g = zarr.open_group(path("truncated-v2.zarr"), mode="w", zarr_format=2)
    g.create_array("0", data=np.arange(16 ** 3, dtype="u2").reshape(16, 16, 16), chunks=(8, 8, 8))
    g.attrs["multiscales"] = multiscale("zyx", [1.0] * 3, [0.0] * 3, "0.4")
    chunk = path("truncated-v2.zarr/0/1.1.1")
    with open(chunk, "rb") as f:
        data = f.read()
    with open(chunk, "wb") as f:
        f.write(data[: len(data) // 2])
    cases["truncated Blosc chunk"] = (path("truncated-v2.zarr"), "blosc")
    # A shard of a store `convert` wrote, cut in half.
    cut = path("truncated-shard.ome.zarr")
    shutil.copytree(converted, cut)
    shard = os.path.join(cut, "0", "c", "0", "0", "0")
    with open(shard, "rb") as f:
        data = f.read()
    with open(shard, "wb") as f:
        f.write(data[: len(data) // 2])
    cases["truncated shard of a converted store"] = (cut, "")
    ome_group("outside.zarr", data=np.zeros((4, 4, 4), "u1"))
    ome_group("traversal.zarr", data=np.zeros((4, 4, 4), "u1"), dataset_path="../outside.zarr/0")
    cases["dataset path out of the store"] = (path("traversal.zarr"), "not a relative path")
    cases["2D image"] = (ome_group("image-2d.zarr", data=np.zeros((8, 8), "u1"), names="yx"), "three spatial axes")
    cases["complex64 samples"] = (ome_group("complex.zarr", data=np.zeros((4, 4, 4), "complex64")), "not supported")
    cases["int64 samples"] = (ome_group("int64.zarr", data=np.zeros((4, 4, 4), "int64")), "not supported")
    cases["shape overflowing a sample count"] = (
        ome_group("overflow.zarr", shape=(2 ** 21, 2 ** 21, 2 ** 22), dtype="u2", chunks=(64, 64, 64)), "overflow")
    cases["shape larger than memory"] = (
        ome_group("huge.zarr", shape=(4000, 4000, 4000), dtype="u1", chunks=(256, 256, 256)), "memory")
    cases["chunks too small to list"] = (
        ome_group("tiny-chunks.zarr", shape=(1000, 1000, 1000), dtype="u1", chunks=(1, 1, 1)), "chunks")
    return cases


def check_hostile(cases):
    for what, (store, words) in cases.items():
        render = ["render", "--output", path("hostile.png"), "--width", "32", "--height", "32"]
        commands = [["info"], ["build"], render]
        if words == "memory":
            # Drawn from disk, such a store is streamed through once to build its octree (a long pass over
            # missing chunks, not an error); read whole, it is refused before anything is read.
            render.append("--in-memory")
        if words == "chunks":
            # A pass over every chunk is refused before it starts: drawn from disk, read whole, converted.
            commands.append(render + ["--in-memory"])
            commands.append(["convert", "--output", path("tiny-converted.ome.zarr")])
        for command in commands:
            status, _, err = run(command[0], "--file", store, *command[1:])
            lines = [ln for ln in err.splitlines() if ln.strip() and not ln.startswith("warning:")]
            ok = (status == 2 and len(lines) == 1 and lines[0].startswith("error:") and words in lines[0]
                  and "panick" not in err and "internal error" not in err.lower())
            check(ok, f"hostile {what}: {command[0]} exited {status} (expected 2 and one 'error:' line naming "
                      f"'{words}'): {err.strip()[:400]!r}")
        print(f"ok: hostile {what}: exit 2, {lines[0][:120] if lines else ''}", flush=True)


# ------------------------------------------------------------------ main


def main():
    print(f"numpy {np.__version__}, zarr {zarr.__version__}, ome-zarr {ome_zarr.__version__}, "
          f"ome-zarr-models {ome_zarr_models.__version__}; work folder {WORK}", flush=True)
    # (a) NGFF 0.5 / Zarr v3, u8, anisotropic, translated.
    a8 = (phantom((21, 26, 30), 1) * 255).round().astype(np.uint8)
    sp8, or8 = (2.5, 0.75, 0.5), (-10.0, 4.0, 12.5)
    v3 = write_v3("v05.ome.zarr", a8, sp8, or8)
    check_foreign("NGFF 0.5 zarr v3 u8", v3, a8, sp8, or8, "u8")
    # (b) NGFF 0.4 / Zarr v2, u16, 5D (t, c, z, y, x); t = c = 0 is what the CLI reads.
    a16 = (phantom((17, 23, 19), 2) * 60000).round().astype(np.uint16)
    a5 = np.stack([np.stack([a16 + 1000 * (3 * t + c) * (t + c > 0) for c in range(3)]) for t in range(2)])
    a5 = np.minimum(a5, 65535).astype(np.uint16)
    a5[0, 0] = a16
    sp16, or16 = (1.0, 0.3, 0.4), (5.0, -2.0, 0.25)
    v2 = write_v2_5d("v04-5d.ome.zarr", a5, sp16, or16)
    check_foreign("NGFF 0.4 zarr v2 u16 5D", v2, a16, sp16, or16, "u16", warned=True)
    # (c) ome_zarr.writer.write_image, its default pyramid, float32 samples.
    f32 = phantom((24, 20, 22), 3).astype(np.float32) * 100 - 20
    spf = (3.0, 1.5, 1.5)
    oz = write_ome_zarr("ome-zarr-writer.ome.zarr", f32, spf)
    check_foreign("ome_zarr.writer f32", oz, f32, spf, (0.0, 0.0, 0.0), "f32")

    # convert: the foreign stores and a built-in dataset, read back by zarr-python.
    c16 = path("converted-v04.ome.zarr")
    run_ok("convert", "--file", v2, "--leaf-size", "8", "--output", c16, "--json")
    check_converted("convert of the NGFF 0.4 store", c16, a16, sp16, or16)
    c8 = path("converted-v05.ome.zarr")
    run_ok("convert", "--file", v3, "--output", c8, "--json")
    check_converted("convert of the NGFF 0.5 store", c8, a8, sp8, or8)
    cv = path("vessels.ome.zarr")
    run_ok("convert", "--dataset", "vessels", "--size", "45", "--type", "u8", "--leaf-size", "8", "--output", cv)
    check_converted("convert --dataset vessels", cv, None, (1.0, 1.0, 1.0), (0.0, 0.0, 0.0))
    # ... and the converted store renders what its source renders.
    for src, dst in [(v2, c16), (v3, c8)]:
        pics = []
        for s in (src, dst):
            pics.append(path(f"cmp-{len(os.listdir(WORK))}.png"))
            run_ok("render", "--file", s, "--in-memory", "--width", "96", "--height", "96", "--output", pics[-1])
        with open(pics[0], "rb") as f1, open(pics[1], "rb") as f2:
            check(f1.read() == f2.read(), f"the converted {dst} renders differently from its source {src}")

    check_hostile(hostile_stores(c16))

    return finish()


if __name__ == "__main__":
    sys.exit(main())
