#!/usr/bin/env bash
# The drop-in check: installs dyngi from BUILD_DIR into a fresh prefix, configures examples/minimal_host
# and examples/own_renderer against that prefix alone (a clean CMake configure, no source tree on their
# include paths), builds both and runs minimal_host on assets/cornell_box.gltf. Writes
# OUT_DIR/minimal_host.png and OUT_DIR/own-build/own_renderer; tests/install runs and checks them.
#   scripts/test_install.sh BUILD_DIR OUT_DIR [FRAMES]
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="$(cd "$1" && pwd)"
out="$2"
frames="${3:-16}"
mkdir -p "$out"
prefix="$out/prefix"
cmake --install "$build" --prefix "$prefix" >"$out/install.log"
cmake -S "$root/examples/minimal_host" -B "$out/host-build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$prefix" \
  >"$out/configure.log"
cmake --build "$out/host-build" -j"$(nproc)" >"$out/build.log"
cmake -S "$root/examples/own_renderer" -B "$out/own-build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$prefix" \
  >"$out/own-configure.log"
cmake --build "$out/own-build" -j"$(nproc)" >"$out/own-build.log"
"$out/host-build/minimal_host" "$root/assets/cornell_box.gltf" "$out/minimal_host.png" "$frames"
