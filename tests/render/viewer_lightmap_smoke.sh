#!/bin/sh
# GLFW smoke test for `prt view` with a texel (lightmap) transfer (run by ctest): bakes a lightmap and a
# per-vertex transfer for a small OBJ with lightmap UVs (a floor of two triangles and a wall standing on
# it), opens the viewer under a virtual X server with both and a disc (sun), saves an EXR screenshot of
# the lightmap, and checks it against `prt render` of the same (the same renderer: rel_rms < 1e-5); then
# the same for the lightmap baked to a .cprt (the texel ship default, drawn compressed).
# Usage: viewer_lightmap_smoke.sh PRT MAKE_FIXTURES. Fails if xvfb-run is not installed.
set -eu
prt="$1"
make_fixtures="$2"
. "$(dirname "$0")/viewer_common.sh"
cat > "$dir/scene.obj" <<'OBJ'
v -1 0 1
v 1 0 1
v 1 0 -1
v -1 0 -1
v -0.5 0 0
v 0.5 0 0
v 0.5 0.8 0
v -0.5 0.8 0
vt 0.02 0.02
vt 0.58 0.02
vt 0.58 0.58
vt 0.02 0.58
vt 0.62 0.02
vt 0.98 0.02
vt 0.98 0.5
vt 0.62 0.5
vn 0 1 0
vn 0 0 1
f 1/1/1 2/2/1 3/3/1 4/4/1
f 5/5/2 6/6/2 7/7/2 8/8/2
OBJ
"$prt" bake "$dir/scene.obj" --transfer interreflected --bounces 1 --bands 3 --samples 64 --lightmap 48x48 -q -o "$dir/lightmap.prt"
"$prt" bake "$dir/scene.obj" --transfer shadowed --bands 3 --samples 64 -q -o "$dir/vertex.prt"
sun="0.4,1,0.3,3,2.5,2,1"
xvfb-run -a -s "-screen 0 1024x768x24" "$prt" view "$dir/scene.obj" "$dir/lightmap.prt" "$dir/vertex.prt" \
  --env "$dir/env.exr" --sun "$sun" --size 160x120 --camera 30,35,auto --rotate 45,0,0 --frames 3 --screenshot "$dir/view.exr"
"$prt" render "$dir/scene.obj" "$dir/lightmap.prt" --env "$dir/env.exr" --sun "$sun" --size 160x120 --camera 30,35,auto \
  --rotate 45,0,0 -q -o "$dir/headless.exr"
"$prt" compare "$dir/view.exr" "$dir/headless.exr" | tee "$dir/compare.txt"
rel_rms_between "$dir/compare.txt" 0 1e-5
# The lightmap was what the viewer drew: its image differs from the per-vertex transfer's (the wall's
# shadow and contact on the floor), yet is lit alike (not black): 1e-3 < rel_rms < 0.5.
"$prt" render "$dir/scene.obj" "$dir/vertex.prt" --env "$dir/env.exr" --sun "$sun" --size 160x120 --camera 30,35,auto \
  --rotate 45,0,0 -q -o "$dir/vertex.exr"
"$prt" compare "$dir/view.exr" "$dir/vertex.exr" | tee "$dir/compare_vertex.txt"
rel_rms_between "$dir/compare_vertex.txt" 1e-3 0.5
# A compressed lightmap (the texel ship default: 16 bands, CPCA), drawn compressed by the viewer as by
# prt render (the same renderer): rel_rms < 1e-5.
"$prt" bake "$dir/scene.obj" --transfer interreflected --bounces 1 --samples 64 --lightmap 48x48 -q -o "$dir/lightmap.cprt"
xvfb-run -a -s "-screen 0 1024x768x24" "$prt" view "$dir/scene.obj" "$dir/lightmap.cprt" \
  --env "$dir/env.exr" --sun "$sun" --size 160x120 --camera 30,35,auto --rotate 45,0,0 --frames 3 --screenshot "$dir/view_cprt.exr"
"$prt" render "$dir/scene.obj" "$dir/lightmap.cprt" --env "$dir/env.exr" --sun "$sun" --size 160x120 --camera 30,35,auto \
  --rotate 45,0,0 -q -o "$dir/headless_cprt.exr"
"$prt" compare "$dir/view_cprt.exr" "$dir/headless_cprt.exr" | tee "$dir/compare_cprt.txt"
rel_rms_between "$dir/compare_cprt.txt" 0 1e-5
echo "viewer lightmap smoke test passed"
