#!/usr/bin/env bash
# Soak test: a dynamic scene (by default the walking fox under the moving spot, --animate fox-and-spot)
# rendered headless for many frames with each technique in GIS, sampling resident memory and the live
# Vulkan allocations every 100 frames (the sample's --memory-log). Fails when either grows by more than 1%
# between the end of the warm-up (the first tenth of the run) and any later sample. Not in CI (about
# 10 minutes per technique on lavapipe); its last result lives in docs/BENCHMARKS.md.
#   scripts/soak.sh [FRAMES] [SIZE]     defaults: 10000 frames at 64x64
#   env: GIS (temporal temporal-bvh; also many-lights, vct), ANIMATE (fox-and-spot), SCENE (the animation's)
#   the camera flying down the 400 m street: ANIMATE=street-flight SCENE=street GIS="temporal vct" scripts/soak.sh
set -euo pipefail
cd "$(dirname "$0")/.."
FRAMES="${1:-10000}"
SIZE="${2:-64x64}"
GIS="${GIS:-temporal temporal-bvh}"
ANIMATE="${ANIMATE:-fox-and-spot}"
SCENE_ARGS=()
[ -n "${SCENE:-}" ] && SCENE_ARGS=(--scene "$SCENE")
bash scripts/setup.sh >/dev/null
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DDYNGI_BUILD_TESTS=ON >/dev/null
cmake --build build -j"$(nproc)" --target dyngi_sample >/dev/null
mkdir -p out/soak
status=0
for gi in $GIS; do
  case "$gi" in
    temporal-bvh) gi_args=(--gi temporal --visibility bvh) ;;
    *) gi_args=(--gi "$gi") ;;
  esac
  log=out/soak/memory_$ANIMATE-$gi.tsv
  start=$(date +%s)
  build/bin/dyngi_sample --headless "${SCENE_ARGS[@]}" --animate "$ANIMATE" "${gi_args[@]}" --frames "$FRAMES" --size "$SIZE" \
    --memory-log "$log" --stats out/soak/stats_$ANIMATE-$gi.json >/dev/null
  secs=$(( $(date +%s) - start ))
  # Columns: frame, rss_kib, vk_allocations, vk_device_bytes. Baseline: the last sample of the warm-up.
  result=$(awk -v frames="$FRAMES" -v gi="$gi" -v secs="$secs" 'NR == 1 { next }
    { f = $1; if (f <= frames / 10) { rss0 = $2; vk0 = $3; mem0 = $4; next }
      if ($2 > rssMax) rssMax = $2; if ($3 > vkMax) vkMax = $3; if ($4 > memMax) memMax = $4; last = $2 }
    END {
      rssGrowth = rss0 > 0 ? 100 * (rssMax - rss0) / rss0 : 0
      vkGrowth = vk0 > 0 ? 100 * (vkMax - vk0) / vk0 : 0
      memGrowth = mem0 > 0 ? 100 * (memMax - mem0) / mem0 : 0
      verdict = (rssGrowth > 1 || vkGrowth > 1 || memGrowth > 1) ? "FAIL" : "ok"
      printf "soak %s: %d frames in %d s; RSS %d -> max %d KiB (%+.2f%%), Vulkan allocations %d -> max %d (%+.2f%%), device bytes %+.2f%%: %s\n",
             gi, frames, secs, rss0, rssMax, rssGrowth, vk0, vkMax, vkGrowth, memGrowth, verdict }' "$log")
  echo "$result"
  case "$result" in *FAIL) status=1 ;; esac
done
exit $status
