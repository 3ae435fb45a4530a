#!/usr/bin/env python3
"""Hostile input for the `hybrid-octree` CLI, run as a new user and an attacker would.

Every case runs the real binary on a malformed file or an extreme argument,
under an address-space cap (`prlimit --as`) and a time limit, and checks the
contract: exit 0 with a right answer, or exit 2 with one short `error:` line
free of control characters; never a signal (abort, out of memory), a panic, an
"internal error", a hang, or a message that echoes the input whole.

usage: hostile_cli.py HYBRID_OCTREE_BINARY [--only SUBSTRING] [--keep DIR]
"""

import gzip
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import zlib

CAP_BYTES = 4 << 30  # address space of each run
TIME_LIMIT = 60  # seconds of each run
MAX_MESSAGE = 1000  # characters of stderr

BIN = sys.argv[1]
ONLY = sys.argv[sys.argv.index("--only") + 1] if "--only" in sys.argv else None
WORK = tempfile.mkdtemp(prefix="hybrid-octree-hostile-")


def path(name):
    return os.path.join(WORK, name)


def write(name, data):
    with open(path(name), "wb") as f:
        f.write(data)
    return path(name)


# ---------------------------------------------------------------- NIfTI files


def nifti(dims=(4, 5, 6), datatype=2, bitpix=8, vox_offset=352.0, data=None, extension=b"\0\0\0\0",
          slope=0.0, inter=0.0, pad_to=None, endian="<"):
    """A NIfTI-1 single file (.nii): header, extension bytes, padding to vox_offset, data."""
    n = dims[0] * dims[1] * dims[2]
    if data is None:
        data = bytes((i * 7) % 251 for i in range(n * bitpix // 8))
    h = bytearray(348)
    struct.pack_into(endian + "i", h, 0, 348)
    struct.pack_into(endian + "8h", h, 40, 3, dims[0], dims[1], dims[2], 1, 1, 1, 1)
    struct.pack_into(endian + "h", h, 70, datatype)
    struct.pack_into(endian + "h", h, 72, bitpix)
    struct.pack_into(endian + "8f", h, 76, 1.0, 1.0, 1.0, 1.0, 1.0, 0, 0, 0)
    struct.pack_into(endian + "f", h, 108, vox_offset)
    struct.pack_into(endian + "f", h, 112, slope)
    struct.pack_into(endian + "f", h, 116, inter)
    h[344:348] = b"n+1\0"
    body = bytes(h) + extension
    start = pad_to if pad_to is not None else 352
    body = body + b"\0" * max(0, start - len(body))
    return body + data


def gz(data):
    return gzip.compress(data, compresslevel=1)


def flip(data, offset, mask=0x01):
    b = bytearray(data)
    b[offset] ^= mask
    return bytes(b)


# ---------------------------------------------------------------- VTK files


def vti(dims=(4, 4, 4), spacing="1 1 1", typ="UInt8", values=None, compressor=None, block=None, extra_attr="",
        declared=None):
    nx, ny, nz = dims
    n = nx * ny * nz
    if values is None:
        values = bytes(i % 256 for i in range(n))
    if compressor == "zlib":
        raw = block if block is not None else values
        comp = zlib.compress(raw, 1)
        size = len(raw) if declared is None else declared
        header = struct.pack("<IIII", 1, size, size, len(comp))
        payload = header + comp
        comp_attr = ' compressor="vtkZLibDataCompressor"'
    else:
        payload = struct.pack("<I", len(values)) + values
        comp_attr = ""
    xml = (
        f'<?xml version="1.0"?>\n<VTKFile type="ImageData" version="1.0" byte_order="LittleEndian" '
        f'header_type="UInt32"{comp_attr}>\n'
        f'<ImageData WholeExtent="0 {nx-1} 0 {ny-1} 0 {nz-1}" Origin="0 0 0" Spacing="{spacing}"{extra_attr}>\n'
        f'<Piece Extent="0 {nx-1} 0 {ny-1} 0 {nz-1}"><PointData Scalars="s">'
        f'<DataArray type="{typ}" Name="s" format="appended" offset="0"/></PointData></Piece>\n'
        f'</ImageData>\n<AppendedData encoding="raw">\n_'
    ).encode()
    return xml + payload + b"\n</AppendedData>\n</VTKFile>\n"


def legacy_vtk(dims=(3, 3, 3), values=None, binary=False):
    nx, ny, nz = dims
    n = nx * ny * nz
    head = (f"# vtk DataFile Version 3.0\nhostile\n{'BINARY' if binary else 'ASCII'}\nDATASET STRUCTURED_POINTS\n"
            f"DIMENSIONS {nx} {ny} {nz}\nORIGIN 0 0 0\nSPACING 1 1 1\nPOINT_DATA {n}\n"
            f"SCALARS s float 1\nLOOKUP_TABLE default\n").encode()
    if values is None:
        values = " ".join(str(i * 0.5) for i in range(n))
    return head + values.encode() + b"\n"


# ---------------------------------------------------------------- the cases

CASES = []


def case(name, args, expect="error", check=None, env=None):
    """expect: 'error' (exit 2), 'ok' (exit 0) or 'either'; check(stdout, stderr) -> problem or None."""
    CASES.append((name, args, expect, check, env))


def info(file, **kw):
    return ["info", "--file", file]


def render(file, *extra):
    return ["render", "--file", file, "--output", path("out.png"), "--width", "64", "--height", "64", *extra]


def value_range(lo, hi):
    def check(out, err):
        m = re.search(r"value range:\s*(\S+) \.\. (\S+)", out)
        if not m:
            return f"no value range in: {out[:200]}"
        got = (float(m.group(1)), float(m.group(2)))
        return None if got == (lo, hi) else f"value range {got}, expected {(lo, hi)}"
    return check


def build_cases():
    n = 4 * 5 * 6
    # NIfTI: where the data start
    data = bytes(range(10, 10 + n))
    case("nii vox_offset 352", info(write("ok.nii", nifti(data=data))), "ok", value_range(10, 10 + n - 1))
    case("nii vox_offset 1024", info(write("off1024.nii", nifti(data=data, vox_offset=1024.0, pad_to=1024))),
         "ok", value_range(10, 10 + n - 1))
    case("nii vox_offset 0 (read as 352, as nibabel does)", info(write("off0.nii", nifti(data=data, vox_offset=0.0))),
         "ok", value_range(10, 10 + n - 1))
    for name, off in [("-1", -1.0), ("nan", float("nan")), ("1e9", 1e9), ("100", 100.0), ("352.5", 352.5)]:
        case(f"nii vox_offset {name}", info(write(f"off{name}.nii", nifti(data=data, vox_offset=off))))
    case("nii bitpix mismatch", info(write("bitpix.nii", nifti(datatype=4, bitpix=8))),
         check=lambda o, e: "--dims" in e and "raw-file advice for a NIfTI file")
    case("nii huge dims", info(write("huge.nii", nifti(dims=(30000, 30000, 30000), data=b"\0" * 64))))
    case("nii negative dims", info(write("neg.nii", nifti(dims=(-4, 5, 6), data=b"\0" * 64))))
    case("nii truncated", info(write("trunc.nii", nifti(data=data)[:-7])))
    case("nii datatype 9999", info(write("dtype.nii", nifti(datatype=9999))))
    case("nii big endian", info(write("be.nii", nifti(data=data, endian=">"))), "ok", value_range(10, 10 + n - 1))
    # gzip trailer and bombs
    good = gz(nifti(data=data))
    case("nii.gz ok", info(write("ok.nii.gz", good)), "ok", value_range(10, 10 + n - 1))
    case("nii.gz flipped data byte", info(write("flip.nii.gz", flip(good, len(good) // 2, 0x10))))
    case("nii.gz bad crc", info(write("crc.nii.gz", flip(good, len(good) - 6))))
    case("nii.gz bad isize", info(write("isize.nii.gz", flip(good, len(good) - 2))))
    case("nii.gz truncated", info(write("trunc.nii.gz", good[:-20])))
    bomb = zlib.compressobj(1, zlib.DEFLATED, 31)
    chunk = b"\0" * (1 << 24)
    header = nifti(dims=(1024, 1024, 1024), data=b"")
    parts = [bomb.compress(header)] + [bomb.compress(chunk) for _ in range(64)] + [bomb.flush()]
    case("nii.gz bomb, 1 GiB declared", info(write("bomb.nii.gz", b"".join(parts))), "either")
    hdr_small = nifti(dims=(8, 8, 8), data=b"")
    parts = [bomb2 := zlib.compressobj(1, zlib.DEFLATED, 31)]
    body = [bomb2.compress(hdr_small)] + [bomb2.compress(chunk) for _ in range(64)] + [bomb2.flush()]
    case("nii.gz bomb, 512 bytes declared, 1 GiB inflated", info(write("bomb2.nii.gz", b"".join(body))))
    ext = nifti(dims=(8, 8, 8), data=b"\0" * 512, extension=b"\1\0\0\0", vox_offset=4e9)
    case("nii extension flag and huge vox_offset", info(write("ext.nii.gz", gz(ext))))
    # VTK XML
    case("vti ok", info(write("ok.vti", vti())), "ok", value_range(0, 63))
    case("vti 1 MB spacing", info(write("spacing.vti", vti(spacing="1 " * 500000))),
         check=lambda o, e: None if len(e) < MAX_MESSAGE else "message echoes the input")
    case("vti escape sequences", info(write("esc.vti", vti(spacing="\x1b[31mred\x1b[0m 1 1"))),
         check=lambda o, e: "raw escape in message" if "\x1b" in e else None)
    case("vti zlib bomb", info(write("bomb.vti", vti(dims=(1024, 1024, 1024), values=b"", compressor="zlib",
                                                  block=b"\0" * (1 << 26)))))
    case("vti zlib block larger than declared",
         info(write("bigblock.vti", vti(dims=(4, 4, 4), compressor="zlib", block=b"\0" * (1 << 30), declared=64))))
    case("vti huge extent", info(write("extent.vti", vti(dims=(100000, 100000, 100000), values=bytes(64)))))
    case("vti zero spacing", info(write("zero.vti", vti(spacing="0 1 1"))))
    case("vti unknown type", info(write("type.vti", vti(typ="Int128"))))
    # legacy VTK
    case("vtk ok", info(write("ok.vtk", legacy_vtk())), "ok")
    case("VTK in capitals", info(write("caps.VTK", legacy_vtk())), "ok")
    case("vtk ascii nan", info(write("nan.vtk", legacy_vtk(values="nan " + " ".join(["1"] * 26)))), "ok")
    case("vtk ascii inf", info(write("inf.vtk", legacy_vtk(values="inf " + " ".join(["1"] * 26)))), "either")
    case("vtk huge dims", info(write("huge.vtk", legacy_vtk(dims=(100000, 100000, 100000), values="1 2 3"))))
    case("vtk truncated", info(write("trunc.vtk", legacy_vtk(values="1 2 3"))))
    # not regular files
    fifo = path("pipe.vti")
    os.mkfifo(fifo)
    case("named pipe", info(fifo))
    os.symlink("/dev/zero", path("zero-dev.vti"))
    case("/dev/zero as .vti", info(path("zero-dev.vti")))
    case("directory", info(WORK))
    case("missing file", info(path("missing.vti")))
    # raw
    write("r.raw", bytes(64))
    case("raw huge dims", ["info", "--file", path("r.raw"), "--dims", "100000,100000,100000", "--type", "u8"])
    case("raw size mismatch", ["info", "--file", path("r.raw"), "--dims", "4,4,5", "--type", "u8"])
    for s in ["1e-7", "1e-30", "1e-300", "1e300"]:
        raw = write(f"sp{s}.raw", bytes((i * 37) % 256 for i in range(16 * 16 * 16)))
        case(f"raw spacing {s} renders", render(raw, "--dims", "16,16,16", "--type", "u8", "--spacing", f"1,1,{s}"),
             "either")
    # arguments
    for size in ["0", "1", "100000", "4294967296", "18446744073709551615"]:
        case(f"--size {size}", ["info", "--dataset", "sphere", "--size", size])
    case("generate --size 3000", ["generate", "--dataset", "sphere", "--size", "3000", "--output", path("g.vti")])
    case("--threads 100000000", ["build", "--dataset", "sphere", "--size", "16", "--threads", "100000000"])
    case("--threads 0", ["build", "--dataset", "sphere", "--size", "16", "--threads", "0"])
    case("render --isovalue -0.5", ["render", "--dataset", "sphere", "--size", "16", "--isovalue", "-0.5",
                                    "--output", path("neg.png"), "--width", "32", "--height", "32"], "ok")
    case("generate x.vtk", ["generate", "--dataset", "sphere", "--size", "8", "--output", path("g.vtk")], "either",
         check=lambda o, e: None if not os.path.exists(path("g.vtk")) or
         b"VTKFile" not in open(path("g.vtk"), "rb").read(200) else "XML written to a .vtk name")
    case("generate x.nii", ["generate", "--dataset", "sphere", "--size", "8", "--output", path("g.nii")])
    case("render x.jpg", ["render", "--dataset", "sphere", "--size", "16", "--output", path("x.jpg")])
    case("render to a missing folder", ["render", "--dataset", "sphere", "--size", "16",
                                        "--output", path("no/such/x.png")],
         check=lambda o, e: "says 'cannot read' for a write" if "cannot read" in e else None)
    # values
    for name in ["constant"]:
        case(f"{name} renders like its reference",
             ["render", "--dataset", name, "--size", "32", "--output", path(f"{name}.png"),
              "--reference", path(f"{name}-ref.png"), "--width", "64", "--height", "64", "--json"], "ok",
             check=rmse_below(0.02))
    for name, values in [("+-1e308", (1e308, -1e308)), ("1e9 offset", (1e9, 1e9 + 1e-3)),
                         ("denormals", (5e-324, 1e-310)), ("max and zero", (1.7976931348623157e308, 0.0))]:
        vals = [values[(i * 7 // 5) % 2] if (i % 3) else values[0] for i in range(16 * 16 * 16)]
        raw = write(f"v{len(CASES)}.raw", struct.pack("<%dd" % len(vals), *vals))
        case(f"f64 {name} renders like its reference",
             ["render", "--file", raw, "--dims", "16,16,16", "--type", "f64", "--output", path("v.png"),
              "--reference", path("v-ref.png"), "--width", "64", "--height", "64", "--json"], "ok",
             check=rmse_below(0.05))


def rmse_below(bound):
    def check(out, err):
        m = re.search(r'"rmse":\s*([0-9.eE+-]+)', out)
        if not m:
            return f"no rmse in output: {out[:300]}"
        return None if float(m.group(1)) <= bound else f"rmse {m.group(1)} above {bound}"
    return check


def run():
    build_cases()
    failures = 0
    for name, args, expect, check, env in CASES:
        if ONLY and ONLY not in name:
            continue
        cmd = ["prlimit", f"--as={CAP_BYTES}", "--", BIN, *args]
        try:
            p = subprocess.run(cmd, capture_output=True, timeout=TIME_LIMIT, env={**os.environ, **(env or {})})
            code, out, err = p.returncode, p.stdout.decode(errors="replace"), p.stderr.decode(errors="replace")
        except subprocess.TimeoutExpired:
            code, out, err = "timeout", "", ""
        problems = []
        if code == "timeout":
            problems.append(f"hang (> {TIME_LIMIT} s)")
        elif code not in (0, 2):
            problems.append(f"exit {code} (signal or crash)")
        else:
            if expect == "error" and code != 2:
                problems.append("accepted, an error was expected")
            if expect == "ok" and code != 0:
                problems.append("refused, success was expected")
            if code == 2:
                if not err.startswith("error: "):
                    problems.append("stderr does not start with 'error: '")
                if len(err) > MAX_MESSAGE:
                    problems.append(f"message of {len(err)} characters")
                if any(c in err for c in "\x1b\x07\x08"):
                    problems.append("control characters in the message")
            if "panicked" in err or "internal error" in err:
                problems.append("panic or internal error")
            if check and code in (0, 2):
                problem = check(out, err)
                if problem:
                    problems.append(problem)
        status = "ok  " if not problems else "FAIL"
        failures += bool(problems)
        first = err.strip().splitlines()[0][:150] if err.strip() else ""
        print(f"{status} {name:48s} exit {code}  {'; '.join(problems)}  {first}")
    print(f"{len(CASES)} cases, {failures} failed")
    if "--keep" not in sys.argv:
        shutil.rmtree(WORK, ignore_errors=True)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(run())
