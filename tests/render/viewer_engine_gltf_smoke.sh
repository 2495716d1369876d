#!/bin/sh
# GLFW smoke test for `prt view` with the engine glTF (run by ctest): bakes Khronos's BoxTextured
# (tests/data, CC-BY 4.0) with --gltf, opens the viewer under a virtual X server with the .glb as both
# mesh and transfer, saves an EXR screenshot, and checks it against `prt render` of the source mesh with
# the .cprt the same bake wrote (rel_rms < 1e-5).
# Usage: viewer_engine_gltf_smoke.sh PRT MAKE_FIXTURES SOURCE_DIR. Fails if xvfb-run is not installed.
set -eu
prt="$1"
make_fixtures="$2"
box="$3/tests/data/BoxTextured/BoxTextured.glb"
. "$(dirname "$0")/viewer_common.sh"
"$prt" bake "$box" --transfer interreflected --bands 3 --samples 32 --bounces 1 --compress 6,2 -q -o "$dir/box.cprt" --gltf "$dir/box.glb"
xvfb-run -a -s "-screen 0 1024x768x24" "$prt" view "$dir/box.glb" "$dir/box.glb" \
  --env "$dir/env.exr" --size 160x120 --camera 30,20,auto --rotate 45,0,0 --frames 3 --screenshot "$dir/view.exr"
"$prt" render "$box" "$dir/box.cprt" --env "$dir/env.exr" --size 160x120 --camera 30,20,auto \
  --rotate 45,0,0 -q -o "$dir/headless.exr"
"$prt" compare "$dir/view.exr" "$dir/headless.exr" | tee "$dir/compare.txt"
rel_rms_between "$dir/compare.txt" 0 1e-5
echo "viewer engine glTF smoke test passed"
