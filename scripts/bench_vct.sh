#!/usr/bin/env bash
# Voxel cone tracing's figures, medians of one run each, printed as the markdown tables
# docs/BENCHMARKS.md keeps:
#  1. stage table: --gi vct on the still Cornell box at 512^2 and 768^2 for 64, 128 and 256^3 voxels.
#     The still scene because on lavapipe the GPU timestamps do not bracket the cone trace in a frame
#     that also re-voxelizes (it then reads about 0.1 ms while the frame grows by its real cost); the
#     voxelize and svo_build columns come from the main job's scene (cornell-dynamic: objects move, so
#     every frame re-voxelizes them and rebuilds the SVO).
#  2. frame table: the main job's scene (cornell-dynamic) with --gi vct (trace scale 2, the default's 0, every
#     pixel traced every frame, fixed unfiltered cones, and the isotropic opaque-axis chain), the temporal
#     VPL technique (--gi temporal, T = 16) and --gi off, in interleaved order, at 512^2 and 768^2.
#  3. image error against the path tracer (still Cornell box, 512^2, 256 spp, 1 bounce).
# Not in CI (timing: about 10 minutes here).     env: FRAMES (24), SIZES ("512 768"), RESOLUTIONS ("64 128 256")
set -euo pipefail
cd "$(dirname "$0")/.."
FRAMES="${FRAMES:-24}"
SIZES="${SIZES:-512 768}"
RESOLUTIONS="${RESOLUTIONS:-64 128 256}"
bash scripts/setup.sh >/dev/null
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DDYNGI_BUILD_TESTS=ON >/dev/null
cmake --build build -j"$(nproc)" --target dyngi_sample dyngi_imgcmp >/dev/null
out=out/bench_vct
mkdir -p "$out"
sample() { build/bin/dyngi_sample --headless --frames "$FRAMES" --warmup 6 "$@" >/dev/null 2>&1; }
field() {  # field FILE EXPRESSION: a number from a stats JSON
  python3 -c "import json,sys; d=json.load(open(sys.argv[1])); print(round(eval(sys.argv[2]), 1))" "$1" "$2"
}

echo "| size | voxels | inject | mips | trace | filter | upsample | voxelize (dynamic) | svo_build (dynamic) | frame (still) |"
echo "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"
for size in $SIZES; do
  for res in $RESOLUTIONS; do
    still="$out/still_${size}_${res}.json" dynamic="$out/dynamic_${size}_${res}.json"
    sample --scene cornell --gi vct --voxel-resolution "$res" --size "${size}x${size}" --stats "$still"
    sample --gi vct --voxel-resolution "$res" --size "${size}x${size}" --stats "$dynamic"
    s="d['stages_ms']"
    echo "| ${size}^2 | ${res}^3 | $(field "$still" "$s['inject']") | $(field "$still" "$s['mips']") | $(field "$still" "$s['trace']") |" \
         "$(field "$still" "$s.get('filter', 0)") | $(field "$still" "$s['upsample']") | $(field "$dynamic" "$s['voxelize']") | $(field "$dynamic" "$s['svo_build']") |" \
         "$(field "$still" "d['frame_ms']['median']") |"
  done
done

echo
echo "| size | --gi off | --gi vct --trace-scale 2 | --gi vct (trace scale 0: 192^2 traced, over 4 frames) | --gi vct --trace-frames 1 | --gi vct --diffuse-filter-radius 0 | --gi vct --anisotropic 0 | --gi temporal (T = 16) |"
echo "| --- | --- | --- | --- | --- | --- | --- | --- |"
for size in $SIZES; do
  row="| ${size}^2"
  for args in "--gi off" "--gi vct --trace-scale 2" "--gi vct" "--gi vct --trace-frames 1" "--gi vct --diffuse-filter-radius 0" "--gi vct --anisotropic 0" "--gi temporal --temporal-sets 16"; do
    f="$out/frame_${size}_$(echo "$args" | tr -d ' -').json"
    # shellcheck disable=SC2086
    sample $args --size "${size}x${size}" --stats "$f"
    row="$row | $(field "$f" "d['frame_ms']['median']")"
  done
  echo "$row |"
done

echo
echo "| image (still Cornell box, 512^2, against the path tracer, 256 spp, 1 bounce) | relMSE | mean ratio |"
echo "| --- | --- | --- |"
build/bin/dyngi_sample --headless --scene cornell --gi path --spp 256 --bounces 1 --size 512x512 --hdr-out "$out/path.exr" >/dev/null 2>&1
for args in "--gi vct --trace-scale 2" "--gi vct" "--gi vct --diffuse-filter-radius 0" "--gi vct --anisotropic 0" "--gi temporal --temporal-sets 16"; do
  img="$out/img_$(echo "$args" | tr -d ' -').exr"
  # shellcheck disable=SC2086
  build/bin/dyngi_sample --headless --scene cornell $args --frames 20 --size 512x512 --hdr-out "$img" >/dev/null 2>&1
  cmp=$(build/bin/dyngi_imgcmp "$img" "$out/path.exr")
  echo "| $args | $(echo "$cmp" | python3 -c "import json,sys; d=json.load(sys.stdin); print(round(d['rel_mse'], 4), '|', round(1 / d['mean_ratio'], 3))") |"
done
