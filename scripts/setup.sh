#!/usr/bin/env bash
# Installs, with apt-get only, what a fresh Debian 12 machine lacks to build, test and run dyngi.
# Idempotent: when every package is already present it does nothing and touches no package list.
set -euo pipefail

PACKAGES=(
  build-essential cmake pkg-config
  libglfw3-dev libglm-dev
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers vulkan-tools
  glslang-dev glslang-tools spirv-tools
  libtinygltf-dev libembree-dev libimgui-dev libstb-dev libtinyexr-dev libpng-dev libjpeg62-turbo-dev
  libgtest-dev libbenchmark-dev nlohmann-json3-dev libtbb-dev
  clang libclang-rt-14-dev libfuzzer-14-dev
  xvfb imagemagick strace time
)

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#PACKAGES[@]} packages present"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "setup: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
$SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
echo "setup: done"
