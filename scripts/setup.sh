#!/usr/bin/env bash
# Installs prt's Debian packages (idempotently: `apt-get update` runs once, and only if something is
# missing), then configures a Release build with Ninja in build/ and builds everything.
# Usage: scripts/setup.sh [--no-build] [extra cmake -D options...]
# Environment: PRT_BUILD_DIR (default build), PRT_EXTRA_PACKAGES (more packages to install).
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  build-essential cmake ninja-build pkg-config git
  libglm-dev libembree-dev libglfw3-dev libopenimageio-dev openimageio-tools catch2 libbenchmark-dev
  libcli11-dev nlohmann-json3-dev libtinyobjloader-dev libtinygltf-dev libimgui-dev
  libegl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri xvfb xauth
)
# shellcheck disable=SC2206
packages+=(${PRT_EXTRA_PACKAGES:-})

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if ((${#missing[@]})); then
  echo "setup: installing ${#missing[@]} Debian packages: ${missing[*]}" >&2
  SUDO=""
  if [ "$(id -u)" != 0 ]; then SUDO="sudo"; fi
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

if [ "${1:-}" = "--no-build" ]; then exit 0; fi
build_dir="${PRT_BUILD_DIR:-build}"
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release "$@" 2>&1 | grep -v -e PyImath -e '^$' >&2 || true
test -f "$build_dir/build.ninja"
cmake --build "$build_dir"
