#!/usr/bin/env bash
# Each technique in a world far larger than a room: the built-in "street" (400 m) and "street-near" (the
# same view, only what lies within 40 m of the camera along the street), each against the path tracer
# of the same scene (1 bounce, as the techniques' defaults). Regions of the image (SIZE 256x192):
#   north facade  never sunlit, lit by bounce light alone: what the GI alone makes;
#   whole image   direct light included, so the engine's one shadow map over the whole scene counts too.
# For each: the technique's mean over the path tracer's, and the voxel size its volume had (the camera's
# surroundings in the street, --voxel-reach; the near copy's bounds). The street's rows against the near
# copy's show what the size of the world costs each technique near the camera.
# Not in CI (about 3 minutes here); docs/QUALITY.md keeps its last result.
# Each configuration is "technique|label|options"; by default the three techniques, then the temporal
# technique with Embree visibility (no voxels on its path), both VPL techniques without the directional
# focus (--directional-reach 0: the sun's VPLs over the whole street), and the temporal technique and VCT
# with the voxel volume over the whole scene (--voxel-reach 0).
#   scripts/large_world.sh ["GI|LABEL|OPTIONS"...]     env: SIZE (256x192), FRAMES (40), SPP (256)
set -euo pipefail
cd "$(dirname "$0")/.."
SIZE="${SIZE:-256x192}"
FRAMES="${FRAMES:-40}"
SPP="${SPP:-256}"
CONFIGS=("$@")
[ ${#CONFIGS[@]} -gt 0 ] || CONFIGS=("temporal|defaults|" "many-lights|defaults|" "vct|defaults|" "temporal|Embree visibility|--visibility bvh"
  "temporal|no focus|--directional-reach 0" "many-lights|no focus|--directional-reach 0" "temporal|Embree, no focus|--visibility bvh --directional-reach 0"
  "temporal|volume over the scene|--voxel-reach 0" "vct|volume over the scene|--voxel-reach 0")
BIN=build/bin
[ -x $BIN/dyngi_sample ] && [ -x $BIN/dyngi_imgcmp ] || { echo "large_world.sh: build dyngi_sample and dyngi_imgcmp first" >&2; exit 2; }
W=${SIZE%x*}
H=${SIZE#*x}
# The north facade: the left of the view, from above the ground's horizon to under the roof line.
FACADE="$((W * 3 / 100)),$((H * 15 / 100)),$((W * 30 / 100)),$((H * 40 / 100))"
out=out/large_world
rm -rf $out
mkdir -p $out
field() { python3 -c "import json,sys; d=json.load(open(sys.argv[1])); print(eval(sys.argv[2]))" "$1" "$2"; }
echo "| technique | setting | scene | voxel size | north facade / path tracer | whole image / path tracer | whole image relMSE |"
echo "| --- | --- | --- | --- | --- | --- | --- |"
for scene in street street-near; do
  $BIN/dyngi_sample --headless --scene $scene --gi path --spp "$SPP" --bounces 1 --size "$SIZE" --frames 1 --hdr-out $out/$scene-path.exr >/dev/null 2>&1
  i=0
  for c in "${CONFIGS[@]}"; do
    IFS='|' read -r gi label opts <<<"$c"
    i=$((i + 1))
    run=$out/$scene-$i
    # shellcheck disable=SC2086
    $BIN/dyngi_sample --headless --scene $scene --gi "$gi" $opts --size "$SIZE" --frames "$FRAMES" --hdr-out $run.exr \
      --out $run.png --stats $run.json >/dev/null 2>&1
    $BIN/dyngi_imgcmp $out/$scene-path.exr $run.exr --region "$FACADE" | tail -1 >$run.cmp.json
    voxel=$(field $run.json "'%.2f m' % d['counts']['voxel_size_m'] if 'voxel_size_m' in d['counts'] else 'none'")
    facade=$(field $run.cmp.json "'%.2f' % d['regions'][0]['ratio']")
    whole=$(field $run.cmp.json "'%.2f' % d['mean_ratio']")
    rel=$(field $run.cmp.json "'%.3f' % d['rel_mse']")
    echo "| $gi | $label | $scene | $voxel | $facade | $whole | $rel |"
  done
done
