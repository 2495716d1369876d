#!/usr/bin/env bash
# Installs prt's Debian packages (idempotently: `apt-get update` runs once, and only if something is
# missing), then configures a Release build with Ninja in build/ and builds everything, or only the
# targets named with --target (scripts/demo.sh builds only `prt`).
# Usage: scripts/setup.sh [--tests] [--no-build] [--target NAME]... [extra cmake -D options...]
#   --tests     also install what the tests need beyond the build: Xvfb (viewer smoke test), Chromium,
#               mono-mcs (compiles and runs the Unity importer against stand-in Unity types),
#               Node.js and the npm packages of probes/threejs (the three.js browser test) and
#               tests/engines (the engines' own code: Babylon.js, Filament, three.js, ktx-parse, the
#               Khronos glTF validator) and web (the three.js PRT runtime), each from its package-lock.json; clang 14 with libFuzzer and
#               llvm-cov (the fuzz targets of tests/fuzz, scripts/fuzz.sh).
#   --no-build  install only.
#   --target    build only this target (repeatable); default: everything (libraries, prt, tests, benches).
#               Open MPI (distributed bakes, -DPRT_WITH_MPI=ON) is installed for a full build or --tests;
#               a build of named targets alone is for one machine unless MPI is already there.
# Environment: PRT_BUILD_DIR (default build), PRT_EXTRA_PACKAGES (more packages to install).
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  build-essential cmake ninja-build pkg-config
  libglm-dev libembree-dev libglfw3-dev libopenimageio-dev catch2 libbenchmark-dev
  libcli11-dev nlohmann-json3-dev libtinyobjloader-dev libtinygltf-dev libdraco-dev libmeshoptimizer-dev
  libimgui-dev
  libegl-dev libgl-dev libopengl-dev libegl-mesa0 libgl1-mesa-dri libeigen3-dev
)
with_tests=0
build=1
cmake_args=()
targets=()
while (($#)); do
  case "$1" in
    --tests) with_tests=1 ;;
    --no-build) build=0 ;;
    --target) targets+=(--target "$2"); shift ;;
    *) cmake_args+=("$1") ;;
  esac
  shift
done
# Open MPI (and the gfortran it pulls in) for a full build or the tests, not for named targets alone:
# the demo's prt runs on one machine. A build/ first configured without MPI gets it now.
if ((with_tests)) || ((${#targets[@]} == 0)); then
  packages+=(libopenmpi-dev openmpi-bin)
  cmake_args+=(-DPRT_WITH_MPI=ON)
fi
if ((with_tests)); then
  # assimp-testmodels: Khronos' glTF sample models (2CylinderEngine, BoxTexcoords) that the engine glTF,
  # unwrap and web tests read from /usr/share/assimp.
  packages+=(xvfb xauth chromium mono-mcs clang-14 libfuzzer-14-dev llvm-14 assimp-testmodels)
  command -v node >/dev/null || packages+=(nodejs)
  command -v npm >/dev/null || packages+=(npm)
fi
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

if ((with_tests)); then
  for folder in probes/threejs tests/engines web; do
    if [ ! -d "$folder/node_modules" ] || [ "$folder/package-lock.json" -nt "$folder/node_modules" ]; then
      echo "setup: installing the npm packages of $folder (npm ci)" >&2
      (cd "$folder" && npm ci --no-audit --no-fund --loglevel=error && touch node_modules) >&2
    fi
  done
fi

if ((build == 0)); then exit 0; fi
build_dir="${PRT_BUILD_DIR:-build}"
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release "${cmake_args[@]}" 2>&1 | grep -v -e PyImath -e '^$' >&2 || true
test -f "$build_dir/build.ninja"
cmake --build "$build_dir" "${targets[@]}"
