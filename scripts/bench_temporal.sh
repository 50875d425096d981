#!/usr/bin/env bash
# Frame time against the temporal set count T (1, 4, 8, 16, 32) at 512 VPLs, 4x4 interleaving, SVO
# visibility, for the scripted scenes static, moving-spot, rotating-object and moving-camera (every pixel
# reprojected from every set each frame); then the image error of
# T = 16 against T = 1 relative to the path tracer (static scene, converged).
# Each configuration runs RUNS times and the table shows the median of the runs' medians: on this shared
# 2-core machine one run's median moves by 10-25% from run to run.
# Usage: scripts/bench_temporal.sh [SIZE] [FRAMES] [RUNS]   (defaults 512x512, 16 measured frames, 3 runs)
# A shorter check of the ratio alone: SCENES="rotating-object static" TS="1 16" ERROR=0 scripts/bench_temporal.sh
# (SCENES and TS choose the rows and columns; TS must hold 1 and 16; ERROR=0 skips the error table).
set -euo pipefail
cd "$(dirname "$0")/.."
SIZE=${1:-512x512}
FRAMES=${2:-16}
RUNS=${3:-3}
SCENES=${SCENES:-static moving-spot rotating-object moving-camera}
TS=${TS:-1 4 8 16 32}
ERROR=${ERROR:-1}
export SCENES TS
BIN=build/bin
mkdir -p out/bench
cmake --build build -j"$(nproc)" --target dyngi_sample dyngi_imgcmp >/dev/null

echo "### Frame time (ms; median of $RUNS runs' medians over $FRAMES frames after warm-up) against T, 512 VPLs, 4x4, $SIZE"
echo
# Runs are interleaved (run r of every T before run r + 1) so a slow phase of the machine hits all T
# alike, and the T=16 / T=1 ratio is taken per run, then its median.
for r in $(seq 1 "$RUNS"); do
  for scene in $SCENES; do
    for T in $TS; do
      warm=$((T + 2))  # left out of the medians: filling the pool and rendering every set once
      $BIN/dyngi_sample --headless --animate $scene --gi temporal --vpls 512 --temporal-sets $T --frames $((warm + FRAMES)) --warmup $warm \
        --size $SIZE --stats out/bench/temporal_${scene}_${T}_$r.json >/dev/null 2>&1
    done
  done
done
python3 - "$RUNS" <<'PY'
import json, statistics, sys
runs = range(1, int(sys.argv[1]) + 1)
ms = lambda s, T, r: json.load(open(f"out/bench/temporal_{s}_{T}_{r}.json"))["frame_ms"]["median"]
import os
scenes, Ts = os.environ["SCENES"].split(), [int(t) for t in os.environ["TS"].split()]
print("| scene | " + " | ".join(f"T={T}" for T in Ts) + " | T=16 / T=1 |")
print("| --- | " + " | ".join("---:" for _ in Ts) + " | ---: |")
for s in scenes:
    cells = [f"{statistics.median(ms(s, T, r) for r in runs):.1f}" for T in Ts]
    ratios = [ms(s, 16, r) / ms(s, 1, r) for r in runs]
    print(f"| {s} | " + " | ".join(cells) + f" | {statistics.median(ratios):.3f} ({min(ratios):.3f}-{max(ratios):.3f}) |")
PY

[ "$ERROR" = 0 ] && exit 0
echo
echo "### Image error against the path tracer (static, 1 bounce, converged: 40 frames)"
echo
$BIN/dyngi_sample --headless --animate static --gi path --bounces 1 --spp 512 --size $SIZE --hdr-out out/bench/t_ref.exr >/dev/null 2>&1
echo "| T | relMSE vs path tracer |"
echo "| ---: | ---: |"
for T in 1 16; do
  $BIN/dyngi_sample --headless --animate static --gi temporal --vpls 512 --temporal-sets $T --frames 40 --size $SIZE \
    --hdr-out out/bench/t_$T.exr >/dev/null 2>&1
  e=$($BIN/dyngi_imgcmp out/bench/t_ref.exr out/bench/t_$T.exr)
  echo "| $T | $(python3 -c "import json,sys; print(round(json.loads(sys.argv[1])['rel_mse'], 5))" "$e") |"
done
