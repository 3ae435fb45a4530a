#!/usr/bin/env bash
# Installs what is missing, builds everything, and runs every test: first
# the fast stage (rustfmt, clang-format, clippy with warnings as errors, the
# layer check of scripts/layers.py, rustdoc with warnings as errors), then the
# CMake build, the Rust unit, integration and doc tests, then CTest (C++
# tests, the find_package consumer, pvbatch plugin tests, the GUI test)
# under Xvfb.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
export PATH="$HOME/.cargo/bin:$PATH"

echo "== cargo fmt --check, clang-format (.clang-format), cargo clippy and cargo doc (warnings are errors), layers =="
cargo fmt --check
find cpp tests/cxx tests/consumer -name '*.cxx' -o -name '*.h' | sort |
  xargs clang-format --dry-run --Werror
CARGO_TARGET_DIR="$PWD/build/clippy" cargo clippy --release --all-targets --locked -- -D warnings
python3 scripts/layers.py
CARGO_TARGET_DIR="$PWD/build/clippy" RUSTDOCFLAGS="-D warnings" cargo doc --no-deps --lib --locked

echo "== CMake build (crate, VTK module, ParaView plugin) =="
bash scripts/build.sh

echo "== cargo test (release, sharing the CMake build's cargo target folder) =="
CARGO_TARGET_DIR="$PWD/build/cargo" cargo test --release --locked

echo "== CTest (under Xvfb) =="
cd build
bash ../scripts/with-xvfb.sh ctest --output-on-failure
