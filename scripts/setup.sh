#!/usr/bin/env bash
# Installs every Debian 12 package shadowref needs to build, test and benchmark.
# Idempotent: when everything is present it prints nothing and exits 0.
# Works as root or, for other users, through sudo.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev libglm-dev libopenimageio-dev openimageio-tools
  libembree-dev libtbb-dev librapidcheck-dev libgtest-dev libgmock-dev
  libbenchmark-dev libbenchmark-tools python3-scipy python3-matplotlib
  libosmesa6-dev libegl-dev libgl-dev libgles-dev libegl-mesa0 libgl1-mesa-dri
  nlohmann-json3-dev libcli11-dev libtinyobjloader-dev libtinygltf-dev
  libmeshoptimizer-dev
  libirrlicht-dev libopenscenegraph-dev xvfb xauth
  clang libclang-rt-14-dev
  chromium
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
[ ${#missing[@]} -eq 0 ] && exit 0

if [ "$(id -u)" -eq 0 ]; then SUDO=(); else SUDO=(sudo); fi
echo "setup: installing ${#missing[@]} Debian packages: ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
"${SUDO[@]}" apt-get update -qq >/dev/null
"${SUDO[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "setup: done" >&2
