#!/usr/bin/env bash
# The Python packages of the OME-Zarr interoperability test (zarr, ome-zarr:
# tests/store/requirements.txt), from PyPI, in a venv under the build tree
# (build/venv): Debian 12's python3 refuses a system-wide pip (PEP 668), and
# nothing is installed into the system Python. A re-run with the same
# requirements does nothing (a stamp holds the requirements installed).
set -euo pipefail
cd "$(dirname "$0")/.."
venv="${HYBRID_OCTREE_VENV:-$PWD/build/venv}"
requirements="$PWD/tests/store/requirements.txt"
stamp="$venv/.requirements"
# Debian's python3 (with python3-venv), not another one first on PATH.
python=/usr/bin/python3
[[ -x $python ]] || python=$(command -v python3)

if [[ -x $venv/bin/python ]] && cmp -s "$requirements" "$stamp"; then
  echo "python-venv: $venv up to date"
  exit 0
fi
if [[ ! -x $venv/bin/python ]]; then
  "$python" -m venv "$venv" || {
    echo "python-venv: '$python -m venv' failed; install Debian's python3-venv (scripts/install-deps.sh as root)" >&2
    exit 1
  }
fi
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check -r "$requirements"
cp "$requirements" "$stamp"
echo "python-venv: $venv ready ($("$venv/bin/python" -c 'import zarr, ome_zarr; print("zarr", zarr.__version__, "ome-zarr", ome_zarr.__version__)'))"
