#!/usr/bin/env bash
# Many-lights benchmark (issue: many-lights GI with SVO visibility). Writes out/bench/*.json and prints
# a markdown table of per-stage medians for 512, 1024 and 2048 VPLs at 768x768 (FRAMES frames after
# warm-up), then the equal-quality comparison against the path tracer at 256x256.
# Usage: scripts/bench_many_lights.sh [FRAMES]   (default 30; takes ~15 minutes on 2 cores)
set -euo pipefail
cd "$(dirname "$0")/.."
FRAMES=${1:-30}
BIN=build/bin
mkdir -p out/bench
cmake --build build -j"$(nproc)" --target dyngi_sample dyngi_imgcmp >/dev/null

for n in 512 1024 2048; do
  $BIN/dyngi_sample --headless --gi many-lights --vpls "$n" --frames $((FRAMES + 2)) --size 768x768 \
    --stats out/bench/svo_$n.json --out out/bench/svo_$n.png >/dev/null
done
python3 - "$FRAMES" <<'PY'
import json, sys
rows = {n: json.load(open(f"out/bench/svo_{n}.json")) for n in (512, 1024, 2048)}
stages = sorted(set().union(*[r["stages_ms"].keys() for r in rows.values()]))
print(f"### Many lights, cornell-dynamic, 768x768, medians over {sys.argv[1]} frames after 2 warm-up\n")
print("| stage (ms) | 512 VPLs | 1024 VPLs | 2048 VPLs |")
print("| --- | ---: | ---: | ---: |")
for s in stages:
    print(f"| {s} | " + " | ".join(f"{rows[n]['stages_ms'].get(s, 0):.1f}" for n in (512, 1024, 2048)) + " |")
print("| **frame** | " + " | ".join(f"**{rows[n]['frame_ms']['median']:.1f}**" for n in (512, 1024, 2048)) + " |")
PY

# Equal quality: the technique's image vs the path tracer's time to reach the same relative MSE.
S=256x256
# The reference uses another seed, so the path tracer's images below are independent of it.
$BIN/dyngi_sample --headless --scene cornell --gi path --bounces 1 --spp 2048 --seed 99 --size $S --hdr-out out/bench/ref.exr >/dev/null
$BIN/dyngi_sample --headless --scene cornell --gi many-lights --vpls 1024 --frames 12 --size $S \
  --hdr-out out/bench/svo_eq.exr --stats out/bench/svo_eq.json >/dev/null
svo_err=$($BIN/dyngi_imgcmp out/bench/ref.exr out/bench/svo_eq.exr)
svo_ms=$(python3 -c "import json; print(json.load(open('out/bench/svo_eq.json'))['frame_ms']['median'])")
echo
echo "### Equal quality at $S (cornell, 1 bounce)"
echo
echo "| renderer | time (ms) | relMSE vs 2048-spp reference |"
echo "| --- | ---: | ---: |"
echo "| many lights, 1024 VPLs (frame median) | $svo_ms | $(python3 -c "import json,sys; print(json.loads(sys.argv[1])['rel_mse'])" "$svo_err") |"
for spp in 1 4 16 64 128 256 512; do
  $BIN/dyngi_sample --headless --scene cornell --gi path --bounces 1 --spp $spp --size $S \
    --hdr-out out/bench/pt_$spp.exr --stats out/bench/pt_$spp.json >/dev/null
  e=$($BIN/dyngi_imgcmp out/bench/ref.exr out/bench/pt_$spp.exr)
  ms=$(python3 -c "import json; print(json.load(open('out/bench/pt_$spp.json'))['cpu_ms']['path_trace'])")
  echo "| path tracer, $spp spp | $ms | $(python3 -c "import json,sys; print(json.loads(sys.argv[1])['rel_mse'])" "$e") |"
done
