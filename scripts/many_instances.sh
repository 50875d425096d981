#!/usr/bin/env bash
# Load-and-render cost of many instances of one mesh: N nodes instancing one quad (written by
# dyngi_make_example_scene --instances N), one frame at 64x64 per --gi mode, wall time and peak RSS
# (GNU time), printed as the markdown table docs/CONTENT.md keeps.
# Not in CI (about a minute here).     env: COUNTS ("20000 200000"), MODES ("off temporal"; a mode
# "temporal-bvh" is the temporal technique with Embree visibility)
set -euo pipefail
cd "$(dirname "$0")/.."
COUNTS="${COUNTS:-20000 200000}"
MODES="${MODES:-off temporal}"
bash scripts/setup.sh >/dev/null
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DDYNGI_BUILD_TESTS=ON >/dev/null
cmake --build build -j"$(nproc)" --target dyngi_sample dyngi_make_example_scene >/dev/null
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "| instances | --gi | wall s | peak RSS MB |"
echo "|---|---|---|---|"
for n in $COUNTS; do
  build/bin/dyngi_make_example_scene "$work/field.gltf" --instances "$n" >/dev/null
  for gi in $MODES; do
    args=(--gi "$gi")
    [ "$gi" = temporal-bvh ] && args=(--gi temporal --visibility bvh)
    /usr/bin/time -f "%e %M" -o "$work/time" build/bin/dyngi_sample --headless --frames 1 --size 64x64 "${args[@]}" \
      --scene "$work/field.gltf" --out "$work/out.png" >/dev/null 2>&1
    read -r wall kib <"$work/time"
    echo "| $n | $gi | $wall | $(( kib / 1024 )) |"
  done
done
