#!/usr/bin/env bash
# Builds and runs the benchmarks in bench/. Each prints its figures next to the issue's targets.
# Usage: scripts/bench.sh [bench_name ...]   (default: all; e.g. scripts/bench.sh bench_sh_eval)
# The machine may be shared: compare ratios measured in the same run, not absolute times across runs.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
all=(bench_sh_eval bench_sh_rotation bench_sh_zonal bench_projection bench_trace bench_bake bench_render
     bench_glossy bench_probes bench_compress)
selected=("$@")
if ((${#selected[@]} == 0)); then selected=("${all[@]}"); fi
for b in "${selected[@]}"; do
  exe=$(find build/bench -maxdepth 1 -type f -name "$b" -perm -u+x | head -1)
  if [ -z "$exe" ]; then echo "bench: $b was not built (skipped)" >&2; continue; fi
  echo "=== $b"
  "$exe"
done
