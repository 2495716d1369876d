#!/usr/bin/env bash
# Installs, builds and runs every test (ctest). Usage: scripts/test.sh [ctest options...]
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh --tests
cd build
ctest --output-on-failure -j"$(nproc)" "$@"
