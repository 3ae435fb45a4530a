#!/usr/bin/env python3
"""TIFF stacks written by tifffile (PyPI) read by the `hybrid-octree` CLI.

1. A real MRI (nibabel's bundled `anatomical.nii`) written by tifffile as an
   ImageJ hyperstack (16-bit, multi-page, calibrated), as a folder of 8-bit
   slices compressed with zlib (unpadded numbers: natural order), and as a
   tiled 32-bit float OME-TIFF: `info` reports numpy's dims, type, spacing
   and value range, `render` draws the same PNG bytes as the same samples
   read as a raw file, and `convert` makes a store that renders the same.
2. Bad stacks (colour pages, an ImageJ hyperstack of two channels, slices of
   two sizes, truncated files, a folder without slices) give exit status 2
   and one `error:` line under an address-space cap: never a signal or a panic.

usage: tiff_interop.py HYBRID_OCTREE_BINARY [--keep DIR]
"""

import json
import os
import re
import sys

import nibabel
import numpy as np
import tifffile

from cli_harness import WORK, check, finish, path, run, run_ok


def raw_args(a, spacing_zyx):
    types = {np.uint8: "u8", np.uint16: "u16", np.float32: "f32"}
    raw = path(f"raw-{len(os.listdir(WORK))}.raw")
    np.ascontiguousarray(a).astype(a.dtype.newbyteorder("<")).tofile(raw)
    return ["--file", raw, "--dims", ",".join(str(n) for n in a.shape[::-1]), "--type", types[a.dtype.type],
            "--spacing", ",".join(str(float(c)) for c in spacing_zyx[::-1])]


def same_png(a_args, b_args, label):
    pics = []
    for args in (a_args, b_args):
        pics.append(path(f"pic-{len(os.listdir(WORK))}.png"))
        out, _ = run_ok("render", *args, "--width", "128", "--height", "96", "--budget-mb", "0.05",
                        "--azimuth", "30", "--elevation", "20", "--json", "--output", pics[-1])
    with open(pics[0], "rb") as f1, open(pics[1], "rb") as f2:
        check(f1.read() == f2.read(), f"{label}: the PNGs differ ({pics[0]}, {pics[1]})")


def check_stack(label, tiff_args, a, spacing_zyx, type_name):
    """`info`, `render` and `convert` of the stack `tiff_args` names, whose samples are `a` (z, y, x)."""
    out, _ = run_ok("info", *tiff_args)
    fields = dict(re.findall(r"^([a-zA-Z ]+):\s+(.*)$", out, re.M))
    dims = [int(n) for n in re.match(r"(\d+) x (\d+) x (\d+)", fields["dims"]).groups()]
    spacing = json.loads(fields["spacing"])
    lo, hi = (float(v) for v in re.match(r"(\S+) \.\. (\S+)", fields["value range"]).groups())
    check(dims == list(a.shape[::-1]), f"{label}: dims {dims} != {list(a.shape[::-1])}")
    check(fields["type"] == type_name, f"{label}: type {fields['type']} != {type_name}")
    check(np.allclose(spacing, spacing_zyx[::-1], rtol=1e-6), f"{label}: spacing {spacing} != {spacing_zyx[::-1]}")
    check(np.isclose(lo, float(a.min())) and np.isclose(hi, float(a.max())), f"{label}: range {lo} .. {hi}")
    raw = raw_args(a, spacing_zyx)
    same_png(tiff_args, raw, f"{label}: render against raw")
    store = path(f"{label.split()[0]}-{len(os.listdir(WORK))}.ome.zarr")
    run_ok("convert", *tiff_args, "--output", store, "--json")
    same_png(["--file", store], raw, f"{label}: the converted store against raw")
    print(f"ok: {label}: {dims} {type_name}, spacing {spacing}, renders and converts equal to raw", flush=True)


def check_fails(label, args, needle):
    status, out, err = run(*args)
    lines = [l for l in err.splitlines() if l.strip()]
    ok = status == 2 and len(lines) == 1 and lines[0].startswith("error:") and needle in err
    check(ok, f"{label}: status {status}, stderr {err.strip()[:300]!r} (expected one 'error:' line with {needle!r})")
    if ok:
        print(f"ok: {label}: {lines[0][:140]}", flush=True)


def main():
    mri = os.path.join(os.path.dirname(nibabel.__file__), "tests", "data", "anatomical.nii")
    img = nibabel.load(mri)
    data = np.asarray(img.dataobj, dtype=np.float64)  # (x, y, z)
    zooms = [float(v) for v in img.header.get_zooms()[:3]]
    scaled = (data - data.min()) / (data.max() - data.min())
    zyx = lambda v: np.ascontiguousarray(np.transpose(v, (2, 1, 0)))
    a16 = zyx(np.round(scaled * 4095).astype(np.uint16))
    a8 = zyx(np.round(scaled * 255).astype(np.uint8))
    af = zyx((scaled * 1000 - 200).astype(np.float32))
    spacing = (zooms[2], zooms[1], zooms[0])

    # An ImageJ stack: calibration in XResolution/YResolution and spacing=.
    ij = path("mri-imagej.tif")
    tifffile.imwrite(ij, a16, imagej=True, resolution=(1 / spacing[2], 1 / spacing[1]),
                     metadata={"spacing": spacing[0], "unit": "mm", "axes": "ZYX"})
    check_stack("imagej u16", ["--file", ij], a16, spacing, "u16")

    # A folder of zlib-compressed 8-bit slices named z1 ... zN (natural order), spacing given.
    folder = path("slices")
    os.makedirs(folder)
    for k, plane in enumerate(a8):
        tifffile.imwrite(os.path.join(folder, f"z{k + 1}.tif"), plane, compression="zlib")
    xyz = ",".join(str(s) for s in spacing[::-1])
    check_stack("folder u8", ["--file", folder, "--spacing", xyz], a8, spacing, "u8")

    # A tiled OME-TIFF of floats (no ImageJ calibration: spacing 1).
    ome = path("mri.ome.tif")
    tifffile.imwrite(ome, af, ome=True, tile=(16, 16), metadata={"axes": "ZYX"})
    check_stack("ome-tiff f32", ["--file", ome], af, (1.0, 1.0, 1.0), "f32")

    # Bad stacks.
    rgb = path("rgb.tif")
    tifffile.imwrite(rgb, np.zeros((4, 8, 8, 3), np.uint8), photometric="rgb")
    check_fails("colour pages", ["info", "--file", rgb], "grayscale")
    hyper = path("hyper.tif")
    tifffile.imwrite(hyper, np.zeros((3, 2, 8, 8), np.uint16), imagej=True, metadata={"axes": "ZCYX"})
    check_fails("ImageJ hyperstack", ["info", "--file", hyper], "2 channels")
    mixed = path("mixed")
    os.makedirs(mixed)
    tifffile.imwrite(os.path.join(mixed, "a1.tif"), np.zeros((8, 8), np.uint8))
    tifffile.imwrite(os.path.join(mixed, "a2.tif"), np.zeros((8, 9), np.uint8))
    check_fails("slices of two sizes", ["info", "--file", mixed], "one size and sample type")
    empty = path("empty")
    os.makedirs(empty)
    check_fails("a folder without slices", ["info", "--file", empty], "no .tif/.tiff slices")
    with open(ij, "rb") as f:
        whole = f.read()
    # Inside the header, a directory, the pixels, and the last page's pixels
    # (tifffile's ImageJ files keep directories after them: the end is not data).
    with tifffile.TiffFile(ij) as t:
        last = t.pages[-1]
        end_of_pixels = last.dataoffsets[-1] + last.databytecounts[-1]
    for cut in (7, 300, len(whole) // 3, end_of_pixels - 5):
        cut_path = path(f"cut-{cut}.tif")
        with open(cut_path, "wb") as f:
            f.write(whole[:cut])
        check_fails(f"truncated at {cut} bytes", ["info", "--file", cut_path], "cut-")
    check_fails("--spacing on a header's file", ["info", "--file", mri, "--spacing", "1,1,1"], "--spacing")

    return finish()


if __name__ == "__main__":
    sys.exit(main())
