#!/usr/bin/env bash
# Set up (if needed), build everything (Release, with tests) into build/, run the whole suite with ctest.
# Render tests run on whatever Vulkan device exists (lavapipe on machines without a GPU) with the
# validation layer on; any validation error fails them.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DDYNGI_BUILD_TESTS=ON >/dev/null
cmake --build build -j"$(nproc)"
cd build
ctest --output-on-failure -j"$(nproc)" "$@"
