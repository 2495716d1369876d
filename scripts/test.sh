#!/usr/bin/env bash
# Installs, builds and runs every test (ctest). Usage: scripts/test.sh [ctest options...], e.g.
# scripts/test.sh -L unit for the quick CPU-only tests; labels: unit, slow, gpu, mpi, node
# (tests/CMakeLists.txt).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh --tests
cd build
unlabelled=$(ctest -N -LE '^(unit|slow|gpu|mpi|node)$' | grep -E '^ *Test +#' || true)
if [ -n "$unlabelled" ]; then
  echo "test: these tests have none of the labels unit, slow, gpu, mpi, node:" >&2
  echo "$unlabelled" >&2
  exit 1
fi
# Catch reads a test name that begins with '-' as an option, so such a test can never run from ctest.
dashed=$(ctest -N | grep -E '^ *Test +#[0-9]+: [A-Za-z0-9_]+:-' || true)
if [ -n "$dashed" ]; then
  echo "test: these test names begin with '-', which Catch reads as an option:" >&2
  echo "$dashed" >&2
  exit 1
fi
ctest --output-on-failure -j"$(nproc)" "$@"
