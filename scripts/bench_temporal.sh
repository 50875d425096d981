#!/usr/bin/env bash
# Frame time against the temporal set count T (1, 4, 8, 16, 32) at 512 VPLs, 4x4 interleaving, SVO
# visibility, for the scripted scenes static, moving-spot and rotating-object; then the image error of
# T = 16 against T = 1 relative to the path tracer (static scene, converged).
# Each configuration runs RUNS times and the table shows the median of the runs' medians: on this shared
# 2-core machine one run's median moves by 10-25% from run to run.
# Usage: scripts/bench_temporal.sh [SIZE] [FRAMES] [RUNS]   (defaults 512x512, 16 measured frames, 3 runs)
set -euo pipefail
cd "$(dirname "$0")/.."
SIZE=${1:-512x512}
FRAMES=${2:-16}
RUNS=${3:-3}
BIN=build/bin
mkdir -p out/bench
cmake --build build -j"$(nproc)" --target dyngi_sample dyngi_imgcmp >/dev/null

echo "### Frame time (ms; median of $RUNS runs' medians over $FRAMES frames after warm-up) against T, 512 VPLs, 4x4, $SIZE"
echo
echo "| scene | T=1 | T=4 | T=8 | T=16 | T=32 |"
echo "| --- | ---: | ---: | ---: | ---: | ---: |"
for scene in static moving-spot rotating-object; do
  row="| $scene |"
  for T in 1 4 8 16 32; do
    # Warm-up (left out of the medians) covers filling the pool and rendering every set once.
    warm=$((T + 2))
    for r in $(seq 1 "$RUNS"); do
      $BIN/dyngi_sample --headless --animate $scene --gi svo --vpls 512 --temporal $T --frames $((warm + FRAMES)) --warmup $warm \
        --size $SIZE --stats out/bench/temporal_${scene}_${T}_$r.json >/dev/null 2>&1
    done
    ms=$(python3 -c "import json, statistics, sys; print(round(statistics.median(json.load(open(f))['frame_ms']['median'] for f in sys.argv[1:]), 1))" \
      out/bench/temporal_${scene}_${T}_*.json)
    row="$row $ms |"
  done
  echo "$row"
done

echo
python3 - "$RUNS" <<'PY'
import json, statistics, sys
runs = int(sys.argv[1])
med = lambda scene, T: statistics.median(json.load(open(f"out/bench/temporal_{scene}_{T}_{r}.json"))["frame_ms"]["median"] for r in range(1, runs + 1))
print("T=16 / T=1 (goal <= 0.1): " + ", ".join(f"{s} {med(s, 16) / med(s, 1):.3f}" for s in ("static", "moving-spot", "rotating-object")))
PY

echo
echo "### Image error against the path tracer (static, 1 bounce, converged: 40 frames)"
echo
$BIN/dyngi_sample --headless --animate static --gi path --bounces 1 --spp 512 --size $SIZE --hdr-out out/bench/t_ref.exr >/dev/null 2>&1
echo "| T | relMSE vs path tracer |"
echo "| ---: | ---: |"
for T in 1 16; do
  $BIN/dyngi_sample --headless --animate static --gi svo --vpls 512 --temporal $T --frames 40 --size $SIZE \
    --hdr-out out/bench/t_$T.exr >/dev/null 2>&1
  e=$($BIN/dyngi_imgcmp out/bench/t_ref.exr out/bench/t_$T.exr)
  echo "| $T | $(python3 -c "import json,sys; print(round(json.loads(sys.argv[1])['rel_mse'], 5))" "$e") |"
done
