#!/usr/bin/env bash
# What `prt bake --footprint area` changes and costs on the bundled statue (docs/conventions.md, "Vertex
# footprint"): bake time for both footprints (3 alternated runs each), and the rendered image of each
# against the path-traced image (`prt reference --image`), with the sun in front and behind.
# Usage: scripts/footprint_study.sh [OUT_DIR]   (default out/footprint; needs a build: scripts/setup.sh)
set -euo pipefail
cd "$(dirname "$0")/.."
prt=build/src/cli/prt
mesh=assets/meshes/guardian_lion_10k.ply
env=assets/env/sunrise.exr
out=${1:-out/footprint}
mkdir -p "$out"
view=(--camera 30,10,auto --size 480x360)
for run in 1 2 3; do
  for fp in vertex area; do
    start=$(date +%s%N)
    "$prt" bake "$mesh" --transfer interreflected --bounces 5 --samples 1024 --footprint "$fp" -q -o "$out/lion_$fp.prt"
    ms=$((($(date +%s%N) - start) / 1000000))
    echo "bake interreflected, 5 bounces, 1024 rays, footprint $fp: $ms ms (run $run)"
  done
done
for rotate in 230 160; do
  "$prt" reference "$mesh" --env "$env" --image --rotate "$rotate,0,0" "${view[@]}" --bounces 5 --samples 1024 \
    --background black -q -o "$out/reference_$rotate.exr" 2>/dev/null
  for fp in vertex area; do
    "$prt" render "$mesh" "$out/lion_$fp.prt" --env "$env" --rotate "$rotate,0,0" "${view[@]}" --background black \
      -o "$out/render_${fp}_$rotate.exr" >/dev/null 2>&1
    echo "lighting turned $rotate degrees, footprint $fp: $("$prt" compare "$out/render_${fp}_$rotate.exr" "$out/reference_$rotate.exr")"
  done
done
