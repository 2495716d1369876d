#!/bin/sh
# GLFW smoke test for `prt view` with a compressed (.cprt) transfer (run by ctest): bakes a glossy
# transfer for the fixture mesh, compresses it with prt compress, opens the viewer under a virtual X
# server with the .cprt and the uncompressed .prt, saves an EXR screenshot of the compressed one, and
# checks it against `prt render` of the .cprt (the same renderer: rel_rms < 1e-5).
# Usage: viewer_cpca_smoke.sh PRT MAKE_FIXTURES. Fails if xvfb-run is not installed.
set -eu
prt="$1"
make_fixtures="$2"
. "$(dirname "$0")/viewer_common.sh"
"$prt" bake "$dir/mesh.ply" --transfer glossy-shadowed --brdf phong:exponent=24,ks=0.5,kd=0.4 --bands 4 --samples 32 -q \
  -o "$dir/glossy.prt"
"$prt" compress "$dir/glossy.prt" --clusters 16 --pca 4 -q -o "$dir/glossy.cprt"
xvfb-run -a -s "-screen 0 1024x768x24" "$prt" view "$dir/mesh.ply" "$dir/glossy.cprt" "$dir/glossy.prt" \
  --env "$dir/env.exr" --size 160x120 --camera 30,20,auto --rotate 45,0,0 --frames 3 --screenshot "$dir/view.exr"
"$prt" render "$dir/mesh.ply" "$dir/glossy.cprt" --env "$dir/env.exr" --size 160x120 --camera 30,20,auto \
  --rotate 45,0,0 -q -o "$dir/headless.exr"
"$prt" compare "$dir/view.exr" "$dir/headless.exr" | tee "$dir/compare.txt"
awk '{ for (i = 1; i <= NF; ++i) if ($i ~ /^rel_rms=/) { split($i, kv, "="); found = 1; ok = (kv[2] + 0 < 1e-5) } }
     END { exit !(found && ok) }' "$dir/compare.txt"
echo "viewer cpca smoke test passed"
