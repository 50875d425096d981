#!/usr/bin/env bash
# What each GI budget knob saves and what the image gives up for it: per technique and knob level, the
# GI's median milliseconds and the final image's error against the reference path tracer with 8 bounces
# (the full transport the VPL techniques' bounce tail carries; relMSE, and the 99th percentile of
# per-pixel relative luminance error), on the static Cornell box. The levels are set as options, each
# one a budget reaches: the gather on one pixel in 2 x 2 and 4 x 4 (--gather-scale
# 2 and 4: the budget's gather_fraction 1/4 and 1/16), the VPLs per frame at their floor (fewer --vpls:
# the temporal technique's floor is K^2 = 16 of a set's 32, the many-lights technique's an eighth), the
# bounce tail's probes one in two (--bounce-tail-stride 2: the budget's tail_stride floor), VCT's
# traced fraction 1/4 and 1/16, then its radiance updated a half and a quarter of the voxels a frame
# (--radiance-frames 2 and 4: a still scene's image is the same; the cost is lag, settle_time.sh).
# docs/QUALITY.md keeps the table. Not in CI (timing; ~5 minutes here).
#   scripts/budget_levels.sh        env: SIZE (256), FRAMES (60), SPP (1024)
set -euo pipefail
cd "$(dirname "$0")/.."
SIZE="${SIZE:-256}"
FRAMES="${FRAMES:-60}"
SPP="${SPP:-1024}"
BIN=build/bin
[ -x $BIN/dyngi_sample ] && [ -x $BIN/dyngi_imgcmp ] || { echo "budget_levels.sh: build dyngi_sample and dyngi_imgcmp first" >&2; exit 2; }
out=out/budget_levels
mkdir -p $out
base=(--headless --scene cornell --size "${SIZE}x${SIZE}")
$BIN/dyngi_sample "${base[@]}" --gi path --spp "$SPP" --bounces 8 --pixel-jitter off --frames 1 --hdr-out $out/path.exr >/dev/null 2>&1
# VCT's default traces one pixel in 2 x 2 at 256^2 (at most 192^2 traced): its fractions 1/4 and 1/16
# are trace scales 4 and 8 there.
levels=(
  "temporal|default|"
  "temporal|gather_fraction 1/4|--gather-scale 2"
  "temporal|gather_fraction 1/16|--gather-scale 4"
  "temporal|vpls_per_frame floor (16 of a set's 32)|--vpls 256"
  "temporal|both floors|--vpls 256 --gather-scale 4"
  "temporal|tail_stride 2|--bounce-tail-stride 2"
  "temporal|all three floors|--vpls 256 --gather-scale 4 --bounce-tail-stride 2"
  "many-lights|default|"
  "many-lights|gather_fraction 1/4|--gather-scale 2"
  "many-lights|gather_fraction 1/16|--gather-scale 4"
  "many-lights|vpls_per_frame floor (1/8)|--vpls 64"
  "many-lights|both floors|--vpls 64 --gather-scale 4"
  "many-lights|tail_stride 2|--bounce-tail-stride 2"
  "many-lights|all three floors|--vpls 64 --gather-scale 4 --bounce-tail-stride 2"
  "vct|default|"
  "vct|trace_fraction 1/4|--trace-scale 4"
  "vct|trace_fraction 1/16|--trace-scale 8"
  "vct|+ radiance_update_fraction 1/2|--trace-scale 8 --radiance-frames 2"
  "vct|+ radiance_update_fraction 1/4|--trace-scale 8 --radiance-frames 4"
)
echo "| technique | level | GI ms (median) | relMSE | p99 relative error |"
echo "| --- | --- | --- | --- | --- |"
i=0
for l in "${levels[@]}"; do
  IFS='|' read -r gi name opts <<<"$l"
  i=$((i + 1))
  # shellcheck disable=SC2086
  $BIN/dyngi_sample "${base[@]}" --gi "$gi" $opts --frames "$FRAMES" --hdr-out $out/$i.exr --stats $out/$i.json >/dev/null 2>&1
  ms=$(python3 -c "import json,sys; print('%.1f' % json.load(open(sys.argv[1]))['gi_ms']['median'])" $out/$i.json)
  cmp=$($BIN/dyngi_imgcmp $out/path.exr $out/$i.exr | tail -1)
  err=$(python3 -c "import json,sys; d=json.loads(sys.argv[1]); print('%.4f | %.3f' % (d['rel_mse'], d['p99_rel_lum']))" "$cmp")
  echo "| $gi | $name | $ms | $err |"
done
