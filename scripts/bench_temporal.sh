#!/usr/bin/env bash
# Frame time against the temporal set count T (1, 4, 8, 16, 32) at 512 VPLs, 4x4 interleaving, SVO
# visibility, for the scripted scenes static, moving-spot and rotating-object; then the image error of
# T = 16 against T = 1 relative to the path tracer (static scene, converged).
# Usage: scripts/bench_temporal.sh [SIZE] [FRAMES]   (defaults 512x512 and 24 measured frames)
set -euo pipefail
cd "$(dirname "$0")/.."
SIZE=${1:-512x512}
FRAMES=${2:-24}
BIN=build/bin
mkdir -p out/bench
cmake --build build -j"$(nproc)" --target dyngi_sample dyngi_imgcmp >/dev/null

echo "### Frame time (ms, median over $FRAMES frames after warm-up) against T, 512 VPLs, 4x4, $SIZE"
echo
echo "| scene | T=1 | T=4 | T=8 | T=16 | T=32 |"
echo "| --- | ---: | ---: | ---: | ---: | ---: |"
for scene in static moving-spot rotating-object; do
  row="| $scene |"
  for T in 1 4 8 16 32; do
    # Warm-up (left out of the medians) covers filling the pool and rendering every set once.
    warm=$((T + 2))
    $BIN/dyngi_sample --headless --animate $scene --gi svo --vpls 512 --temporal $T --frames $((warm + FRAMES)) --warmup $warm \
      --size $SIZE --stats out/bench/temporal_${scene}_$T.json >/dev/null
    ms=$(python3 -c "import json; print(round(json.load(open('out/bench/temporal_${scene}_$T.json'))['frame_ms']['median'], 1))")
    row="$row $ms |"
  done
  echo "$row"
done

echo
echo "### Image error against the path tracer (static, 1 bounce, converged: 40 frames)"
echo
$BIN/dyngi_sample --headless --animate static --gi path --bounces 1 --spp 512 --size $SIZE --hdr-out out/bench/t_ref.exr >/dev/null
echo "| T | relMSE vs path tracer |"
echo "| ---: | ---: |"
for T in 1 16; do
  $BIN/dyngi_sample --headless --animate static --gi svo --vpls 512 --temporal $T --frames 40 --size $SIZE \
    --hdr-out out/bench/t_$T.exr >/dev/null
  e=$($BIN/dyngi_imgcmp out/bench/t_ref.exr out/bench/t_$T.exr)
  echo "| $T | $(python3 -c "import json,sys; print(round(json.loads(sys.argv[1])['rel_mse'], 5))" "$e") |"
done
