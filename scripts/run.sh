#!/usr/bin/env bash
# The main job: set up (if needed), build Release into build/, run the sample scene with GI
# (--gi temporal: incremental temporal VPLs with SVO visibility). With no display it renders the default
# scene headless to out/frame.png + out/stats.json and prints the per-stage table; with a display it
# opens the window. Extra arguments go to dyngi_sample (a later --gi overrides the default here).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
# Tests stay configured (only the sample is built here): turning them off would leave stale test
# binaries in build/ for the next scripts/test.sh-less ctest run.
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DDYNGI_BUILD_TESTS=ON >/dev/null
cmake --build build -j"$(nproc)" --target dyngi_sample
mkdir -p out
if [ -n "${DISPLAY:-}" ] || [ -n "${WAYLAND_DISPLAY:-}" ]; then
  exec build/bin/dyngi_sample --gi temporal "$@"
else
  exec build/bin/dyngi_sample --headless --gi temporal --out out/frame.png --hdr-out out/frame.exr --stats out/stats.json "$@"
fi
