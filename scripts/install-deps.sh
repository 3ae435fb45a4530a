#!/usr/bin/env bash
# Installs everything HybridOctree needs on Debian 12, from Debian's packages.
# Safe to re-run: it skips apt when every package is already installed.
set -euo pipefail

# libopenmpi-dev and libdouble-conversion-dev: ParaView's CMake package needs them but paraview-dev does not pull them in.
# openmpi-bin: mpiexec, for the 2-rank pvbatch test of the representation.
# libglew-dev: VTK::RenderingOpenGL2 (the volume mapper) includes <GL/glew.h> and links GLEW.
# libfontconfig1-dev, libfreetype-dev, fonts-dejavu-core: the CLI's plots (plotters draws text through fontconfig).
# qtbase5-dev, libqt5svg5-dev, qttools5-dev: the plugin's GUI behaviour (cpp/Plugin/) builds against ParaView's Qt 5 client (its CMake package asks for Qt5 Widgets, Svg and Help);
# libqt5opengl5-dev, libxml2-dev, libhdf5-dev, libnetcdf-dev, libboost-dev: the CMake targets of VTK's modules that ParaView's pqComponents links name these packages.
# clang-format: the test command's first stage checks the C++ against .clang-format.
# python3-pyqt5: the GUI test (tests/gui/) reads the ParaView window's widgets from its Python.
# python3-venv: the venv (build/venv, scripts/python-venv.sh) that holds zarr and ome-zarr from PyPI for the OME-Zarr interoperability test.
PACKAGES=(paraview paraview-dev python3-paraview libopenmpi-dev openmpi-bin libdouble-conversion-dev liblzma-dev libglew-dev xvfb xauth cmake make g++ pkg-config python3 libfontconfig1-dev libfreetype-dev fonts-dejavu-core qtbase5-dev libqt5svg5-dev qttools5-dev libqt5opengl5-dev libxml2-dev libhdf5-dev libnetcdf-dev libboost-dev clang-format python3-pyqt5 python3-venv)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done
if ((${#missing[@]})); then
  if [[ $(id -u) -ne 0 ]]; then
    echo "install-deps: missing Debian packages: ${missing[*]}; run this script as root (or with sudo)" >&2
    exit 1
  fi
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -q
  apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

# Rust: the crate needs rustc >= 1.91 (Debian 12's own rustc is 1.63, too old).
if ! command -v cargo >/dev/null 2>&1 && [[ -x "$HOME/.cargo/bin/cargo" ]]; then
  export PATH="$HOME/.cargo/bin:$PATH"
fi
if ! command -v cargo >/dev/null 2>&1; then
  echo "install-deps: cargo not found; install a Rust toolchain >= 1.91 (rustup) and re-run" >&2
  exit 1
fi
rustc_minor=$(rustc --version | sed -E 's/^rustc 1\.([0-9]+).*/\1/')
if ((rustc_minor < 91)); then
  echo "install-deps: $(rustc --version) is too old; HybridOctree needs rustc >= 1.91 (rustup update)" >&2
  exit 1
fi
# rustfmt and clippy: the test command's first stage.
if ! cargo fmt --version >/dev/null 2>&1 || ! cargo clippy --version >/dev/null 2>&1; then
  if command -v rustup >/dev/null 2>&1; then
    rustup component add rustfmt clippy
  else
    echo "install-deps: cargo fmt or cargo clippy missing; install the rustfmt and clippy components" >&2
    exit 1
  fi
fi
# zarr and ome-zarr (PyPI) in build/venv, for tests/store/interop.py.
bash "$(dirname "$0")/python-venv.sh"
echo "install-deps: Debian packages, $(cargo --version) and the test venv ready"
