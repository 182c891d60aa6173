#!/usr/bin/env bash
# Installs every Debian 12 package shadowref needs to build, test and benchmark, then the web
# harnesses' and gltf-transform's npm packages (their package-lock.json, from the npm registry, with `npm ci`).
# Idempotent: when everything is present it prints nothing and exits 0.
# Works as root or, for other users, through sudo.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev libglm-dev libopenimageio-dev openimageio-tools
  libembree-dev libtbb-dev librapidcheck-dev libgtest-dev libgmock-dev
  libbenchmark-dev libbenchmark-tools python3-scipy python3-matplotlib python3-yaml python3-jsonschema
  libosmesa6-dev libegl-dev libgl-dev libgles-dev libegl-mesa0 libgl1-mesa-dri
  nlohmann-json3-dev libcli11-dev libtinyobjloader-dev libtinygltf-dev
  libmeshoptimizer-dev zlib1g-dev libpng-dev libre2-dev
  libirrlicht-dev libopenscenegraph-dev xvfb xauth
  clang libclang-rt-14-dev
  chromium
)
# Node and npm for engines/web/ (Debian 12: nodejs 18, npm 9). A machine that already has them from
# elsewhere (NodeSource's nodejs bundles npm) keeps them: Debian's npm would conflict with it.
command -v node >/dev/null 2>&1 || packages+=(nodejs)
command -v npm >/dev/null 2>&1 || packages+=(npm)

# The npm packages, exactly as each lockfile pins them: the web harnesses' (engines/web) and
# gltf-transform, the glTF tool other than ours that pack/tests/gltf_transform_test.py rewrites the
# pack's scene.gltf with (pack/tests/gltf_transform). A folder is skipped when its node_modules was
# installed from this very lockfile (the stamp is its copy). --ignore-scripts: no package runs code
# at install time (puppeteer-core downloads no browser; the harness uses Debian's chromium; sharp,
# which gltf-transform's texture commands load, comes as its prebuilt @img packages).
npm_folder() {
  local dir="$1"
  if cmp -s "$dir/package-lock.json" "$dir/node_modules/.shadowref-lock.json" 2>/dev/null; then return 0; fi
  echo "setup: npm ci in ${dir#"$root"/}" >&2
  (cd "$dir" && npm ci --ignore-scripts --no-audit --no-fund --loglevel=error >/dev/null)
  cp "$dir/package-lock.json" "$dir/node_modules/.shadowref-lock.json"
}
web_packages() {
  npm_folder "$root/engines/web"
  npm_folder "$root/pack/tests/gltf_transform"
}

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if [ ${#missing[@]} -eq 0 ]; then
  web_packages
  exit 0
fi

if [ "$(id -u)" -eq 0 ]; then SUDO=(); else SUDO=(sudo); fi
echo "setup: installing ${#missing[@]} Debian packages: ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
"${SUDO[@]}" apt-get update -qq >/dev/null
"${SUDO[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
web_packages
echo "setup: done" >&2
