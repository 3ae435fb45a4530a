#!/usr/bin/env bash
# Regenerates docs/images/paraview-gui.png: the ParaView GUI under Xvfb with
# the "Hybrid Octree Volume" representation (scripts/gui_screenshot.py),
# its window resized and the Properties panel scrolled to the Hybrid Octree
# group with xdotool, the screen grabbed with xwd.
# Needs, besides install-deps: apt-get install x11-apps netpbm xdotool
#   bash scripts/gui_screenshot.sh            (after bash scripts/build.sh)
set -euo pipefail
cd "$(dirname "$0")/.."
if [[ -z "${DISPLAY:-}" ]]; then
  exec bash scripts/with-xvfb.sh bash "$0" "$@"
fi
for tool in xwd xwdtopnm pnmtopng xdotool; do
  command -v "$tool" >/dev/null || { echo "gui_screenshot: $tool missing (apt-get install x11-apps netpbm xdotool)" >&2; exit 1; }
done
data=$(mktemp -d)
trap 'rm -rf "$data"' EXIT
build/cargo/release/hybrid-octree generate --dataset shepp-logan --size 128 --output "$data/phantom.vti" >/dev/null
HO_PLUGIN=$(find build/lib -name HybridOctree.so | head -n 1) HO_DATA="$data/phantom.vti" \
  paraview --script="$PWD/scripts/gui_screenshot.py" >"$data/paraview.log" 2>&1 &
pid=$!
sleep 30
xdotool key Escape # the welcome dialog
win=$(xdotool search --onlyvisible --name "ParaView" | head -1)
xdotool windowmove "$win" 0 0 windowsize "$win" 1280 1024
sleep 4
xdotool key Escape
xdotool mousemove 150 800
for _ in 1 2 3 4 5 6; do xdotool click 5; sleep 0.2; done
sleep 8
mkdir -p docs/images
xwd -root -silent | xwdtopnm 2>/dev/null | pnmtopng >docs/images/paraview-gui.png
kill "$pid"
echo "wrote docs/images/paraview-gui.png"
