#!/bin/sh
# GLFW smoke test for `prt view` of a mixed pair (run by ctest): bakes the room of
# tests/lightmap/mixed_scenes.h (floor and wall per texel, box per vertex) into ROOM.prt and
# ROOM.vertices.prt, opens the viewer under a virtual X server with the per-vertex file alone (it loads
# its partner and starts on the pair's one-frame entry) and a disc (sun), saves an EXR screenshot, and
# checks it against `prt render` of the pair (the same renderer: rel_rms < 1e-5). The screenshot is the
# pair, not one of its files drawn over the whole mesh: it differs from the same scene baked all per
# texel and all per vertex (1e-3 < rel_rms < 0.5 each).
# Usage: viewer_mixed_smoke.sh PRT MAKE_FIXTURES. Fails if xvfb-run is not installed.
set -eu
prt="$1"
make_fixtures="$2"
. "$(dirname "$0")/viewer_common.sh"
bake="--transfer interreflected --bounces 1 --bands 3 --samples 64 -q"
"$prt" bake "$dir/room.gltf" --lightmap 48 --texel-parts Floor,Wall $bake -o "$dir/mixed.prt"
"$prt" bake "$dir/room.gltf" --lightmap 48 $bake -o "$dir/texel.prt"
"$prt" bake "$dir/room.gltf" $bake -o "$dir/vertex.prt"
sun="0.6,0.55,0.45,3,2.6,2.2,1"
view="--env $dir/env.exr --sun $sun --size 160x120 --camera 215,50,auto --rotate 30,0,0"
xvfb-run -a -s "-screen 0 1024x768x24" "$prt" view "$dir/room.gltf" "$dir/mixed.vertices.prt" $view --frames 3 \
  --screenshot "$dir/view.exr"
"$prt" render "$dir/room.gltf" "$dir/mixed.prt" $view -q -o "$dir/headless.exr"
"$prt" compare "$dir/view.exr" "$dir/headless.exr" | tee "$dir/compare.txt"
rel_rms_between "$dir/compare.txt" 0 1e-5
for single in texel vertex; do
  "$prt" render "$dir/room.gltf" "$dir/$single.prt" $view -q -o "$dir/$single.exr"
  "$prt" compare "$dir/view.exr" "$dir/$single.exr" | tee "$dir/compare_$single.txt"
  rel_rms_between "$dir/compare_$single.txt" 1e-3 0.5
done
echo "viewer mixed smoke test passed"
