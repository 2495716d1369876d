#!/bin/sh
# GLFW smoke test for `prt view` of a textured asset (run by ctest): the BoxTextured sample model baked,
# opened in the viewer under a virtual X server, an EXR screenshot saved; it must equal `prt render` of
# the same view (the same renderer, texture per pixel: tests/render/test_render_texture.cpp checks that
# against closed forms) to float rounding.
# Usage: viewer_texture_smoke.sh PRT MAKE_FIXTURES SOURCE_DIR.
set -eu
prt="$1"
make_fixtures="$2"
source_dir="$3"
. "$(dirname "$0")/viewer_common.sh"
box="$source_dir/tests/data/BoxTextured/BoxTextured.gltf"
"$prt" bake "$box" --transfer shadowed --bands 3 --samples 64 -q -o "$dir/box.prt"
xvfb-run -a -s "-screen 0 1024x768x24" "$prt" view "$box" "$dir/box.prt" --env "$dir/env.exr" --size 160x120 \
  --camera 30,20,auto --frames 3 --screenshot "$dir/shot.exr"
test -s "$dir/shot.exr"
"$prt" render "$box" "$dir/box.prt" --env "$dir/env.exr" --size 160x120 --camera 30,20,auto -q -o "$dir/headless.exr"
"$prt" compare "$dir/shot.exr" "$dir/headless.exr" | tee "$dir/same.txt"
rel_rms_between "$dir/same.txt" 0 1e-5
echo "viewer texture smoke test passed"
