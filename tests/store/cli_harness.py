"""The `hybrid-octree` CLI run by the interoperability tests: each run under an
address-space cap and a time limit, checks counted, a work folder kept on
failure (or with `--keep DIR`).

usage in a test: `from cli_harness import WORK, path, check, run, run_ok, finish`,
the binary the script's first argument.
"""

import os
import shutil
import subprocess
import sys
import tempfile

CAP_BYTES = 4 << 30  # address space of each run
TIME_LIMIT = 120  # seconds of each run
BIN = sys.argv[1]
WORK = sys.argv[sys.argv.index("--keep") + 1] if "--keep" in sys.argv else tempfile.mkdtemp(prefix="ho-interop-")
os.makedirs(WORK, exist_ok=True)
FAILURES = []
PASSED = [0]


def path(name):
    return os.path.join(WORK, name)


def check(ok, what):
    if ok:
        PASSED[0] += 1
    else:
        FAILURES.append(what)
        print("FAIL:", what, flush=True)


def run(*args):
    """The CLI under the address-space cap and time limit: (status, stdout, stderr)."""
    cmd = ["prlimit", f"--as={CAP_BYTES}", "timeout", str(TIME_LIMIT), BIN, *map(str, args)]
    p = subprocess.run(cmd, capture_output=True, text=True)
    return p.returncode, p.stdout, p.stderr


def run_ok(*args):
    status, out, err = run(*args)
    if status != 0:
        raise SystemExit(f"FAIL: {' '.join(map(str, args))} exited {status}: {err.strip()[:500]}")
    return out, err


def finish():
    """Prints the count, removes the work folder when all passed (unless kept); the exit status."""
    print(f"{PASSED[0]} passed, {len(FAILURES)} failed", flush=True)
    if "--keep" not in sys.argv and not FAILURES:
        shutil.rmtree(WORK, ignore_errors=True)
    return 1 if FAILURES else 0
