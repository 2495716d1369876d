#!/usr/bin/env bash
# The main job on the bundled assets: install, build, bake the bundled mesh's interreflected transfer
# (each vertex's value averaged over the surface it covers, prt bake's default footprint: no dark
# specks at the scan's folds), then render it headless (EGL, no display needed) under the bundled environment, twice:
# as lit in the README and with the lighting rotated. Outputs in out/.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh --target prt   # only what the demo runs: the libraries and the prt executable
prt=build/src/cli/prt
mesh=assets/meshes/guardian_lion_10k.ply
env=assets/env/sunrise.exr
mkdir -p out
"$prt" bake "$mesh" --transfer interreflected --bands 5 --samples 1024 -o out/lion.prt
view=(--camera 30,10,auto --size 960x720 --exposure -1)
"$prt" render "$mesh" out/lion.prt --env "$env" --rotate 230,0,0 "${view[@]}" -o out/demo.png
"$prt" render "$mesh" out/lion.prt --env "$env" --rotate 160,0,0 "${view[@]}" -o out/demo_rotated.png
"$prt" light "$env" --bands 5 -o out/sunrise_sh.json --preview out/sunrise_sh.png
echo "demo: wrote out/demo.png and out/demo_rotated.png (and out/lion.prt, out/sunrise_sh.json, out/sunrise_sh.png)"
