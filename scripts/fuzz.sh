#!/usr/bin/env bash
# Runs every cargo-fuzz target of fuzz/ for SECONDS each (default 300), one
# after another at low priority, with overflow checks (-a). Needs
# `cargo install cargo-fuzz` and nightly or RUSTC_BOOTSTRAP=1 on stable.
# New inputs go to fuzz/corpus/<target> (not committed); the committed seeds
# are fuzz/seeds/<target>; crashes land in fuzz/artifacts/<target>.
# Usage: scripts/fuzz.sh [SECONDS] [TARGET...]
set -euo pipefail
cd "$(dirname "$0")/../fuzz"
seconds=${1:-300}
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(vti vtk nifti raw hopoints)
for t in "${targets[@]}"; do
    mkdir -p "corpus/$t"
    echo "== $t: ${seconds}s"
    RUSTC_BOOTSTRAP=1 nice -n 19 cargo fuzz run -O -a "$t" "corpus/$t" "seeds/$t" -- \
        -max_total_time="$seconds" -max_len=8192 -rss_limit_mb=2048 -timeout=10 -print_final_stats=1
done
