#!/usr/bin/env bash
# Installs what is missing, builds everything, and runs the main job on the
# built-in 256^3 Shepp-Logan phantom: the CLI builds and describes its Volume
# Octree and its isosurface (DiscMC with face compression, and what that costs
# in accuracy), renders it under an 8 MB texture budget with a translucent
# isosurface (hybrid-octree-render.png, against the full-resolution reference
# hybrid-octree-reference.png), keeps it at every 4th sample plus error points
# (hybrid-octree-points-{lowres,hybrid,reference}.png and their 4x difference
# pictures -lowres-diff, -hybrid-diff), does the same on the built-in vessels
# angiogram with the optimized low resolution (hybrid-octree-vessels-*.png), then pvbatch loads the ParaView plugin, applies the Hybrid
# Octree filter to the same volume, and renders its node boxes and isosurface
# to hybrid-octree-demo.png, and vtkHybridOctreeVolumeMapper (OpenGL, from
# Python) draws the volume and translucent isosurface at the default 64 MB
# budget to hybrid-octree-mapper.png, with its error against the reference.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
export PATH="$HOME/.cargo/bin:$PATH"
bash scripts/build.sh

cli=build/cargo/release/hybrid-octree
plugin=$(find build/lib -name HybridOctree.so | head -n 1)
size=${SIZE:-256}

echo "== hybrid-octree build --dataset shepp-logan --size $size =="
"$cli" build --dataset shepp-logan --size "$size" --tolerance 0.01

echo "== hybrid-octree surface --dataset shepp-logan --size $size --isovalue 0.5 --distance =="
"$cli" surface --dataset shepp-logan --size "$size" --isovalue 0.5 --distance

echo "== hybrid-octree render --dataset shepp-logan --size $size --budget-mb 8 (translucent isosurface, vs the reference) =="
"$cli" render --dataset shepp-logan --size "$size" --budget-mb 8 --isovalue 0.5 --surface-opacity 0.4 \
  --output hybrid-octree-render.png --reference hybrid-octree-reference.png

echo "== hybrid-octree points --dataset shepp-logan --size $size --factor 4 --threshold 0.1 (low resolution + error points, vs the reference) =="
"$cli" points --dataset shepp-logan --size "$size" --factor 4 --threshold 0.1 \
  --output hybrid-octree-points.hop --render hybrid-octree-points

echo "== hybrid-octree points --dataset vessels --size $size --factor 4 --threshold 0.1 --max-overestimate 0.1 (fine detail: optimized low resolution + points) =="
"$cli" points --dataset vessels --size "$size" --factor 4 --threshold 0.1 --max-overestimate 0.1 \
  --output hybrid-octree-vessels.hop --render hybrid-octree-vessels

echo "== ParaView (pvbatch) with the HybridOctree plugin =="
vti=$(mktemp --suffix=.vti)
trap 'rm -f "$vti"' EXIT
"$cli" generate --dataset shepp-logan --size "$size" --type f32 --output "$vti"
bash scripts/with-xvfb.sh \
  pvbatch scripts/demo_pvbatch.py --plugin "$plugin" --input "$vti" --output hybrid-octree-demo.png

echo "== vtkHybridOctreeVolumeMapper (OpenGL) from pvbatch, 64 MB, translucent isosurface, vs the reference =="
PYTHONPATH="$PWD/build/lib/python3.11/site-packages" bash scripts/with-xvfb.sh \
  pvbatch scripts/demo_mapper.py --input "$vti" --output hybrid-octree-mapper.png \
  --reference hybrid-octree-reference.png
