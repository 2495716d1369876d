#!/usr/bin/env bash
# Proves that prt is a library others can link: configures the core module alone (-DPRT_COMPONENTS=core)
# and checks from CMake's trace that the configure never searched for Embree, OpenImageIO, GL, GLFW, MPI,
# Eigen or the mesh loaders; installs it to a prefix; then builds tests/install/consumer, a separate
# CMake project that does find_package(prt COMPONENTS core), against that prefix and runs it (it checks
# SH values against closed forms). With a second folder holding a full build (scripts/setup.sh's build/),
# also installs that and builds the consumer against every component, which links them all.
# Usage: scripts/check_install.sh [core build folder, default build-core] [full build folder]
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build-core}"
prefix="$PWD/$build/prefix"
rm -rf "$build"
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DPRT_COMPONENTS=core \
  --trace-expand --trace-redirect="$build.trace" >/dev/null
searched=$(grep -oE 'find_(package|dependency)\((embree|OpenImageIO|OpenGL|glfw3|MPI|Eigen3|tinyobjloader|TinyGLTF|PkgConfig)' \
  "$build.trace" | sort -u || true)
rm -f "$build.trace"
if [ -n "$searched" ]; then
  echo "check_install: the core-only configure searched for packages core does not use: $searched" >&2
  exit 1
fi
cmake --build "$build"
cmake --install "$build" --prefix "$prefix" >/dev/null
cmake -S tests/install/consumer -B "$build/consumer" -G Ninja -DCMAKE_PREFIX_PATH="$prefix" >/dev/null
cmake --build "$build/consumer"
"$build/consumer/prt_consumer"
echo "check_install: core-only configure found no other package; installed prt::core linked and ran"
if [ -n "${2:-}" ]; then
  full_prefix="$PWD/$build/prefix-full"
  cmake --install "$2" --prefix "$full_prefix" >/dev/null
  components=$(find "$full_prefix" -name 'prt_*Targets.cmake' -printf '%f\n' | sed 's/^prt_\(.*\)Targets.cmake$/\1/' | sort | tr '\n' ' ')
  cmake -S tests/install/consumer -B "$build/consumer-full" -G Ninja -DCMAKE_PREFIX_PATH="$full_prefix" \
    -DPRT_CONSUMER_COMPONENTS="$(echo $components | tr ' ' ';')" >/dev/null
  cmake --build "$build/consumer-full"
  "$build/consumer-full/prt_consumer"
  echo "check_install: every installed component ($components) found, linked and ran"
fi
