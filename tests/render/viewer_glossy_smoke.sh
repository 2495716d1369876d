#!/bin/sh
# GLFW smoke test for `prt view` with a glossy transfer (run by ctest): bakes a glossy transfer for the
# fixture mesh, opens the viewer under a virtual X server with a glossy and a diffuse transfer, saves an
# EXR screenshot of the glossy one, and checks it against `prt render` of the same view (the same
# renderer: rel_rms < 1e-5); then the same with --brdf overriding the baked BRDF.
# Usage: viewer_glossy_smoke.sh PRT MAKE_FIXTURES. Fails (exit 1) if xvfb-run is not installed:
# scripts/setup.sh --tests installs it, so its absence is a broken setup, not a reason to skip.
set -eu
prt="$1"
make_fixtures="$2"
if ! command -v xvfb-run >/dev/null 2>&1; then
  echo "FAILED: xvfb-run is not installed (scripts/setup.sh --tests installs xvfb); the viewer needs an X display"
  exit 1
fi
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
"$make_fixtures" "$dir"
"$prt" bake "$dir/mesh.ply" --transfer glossy-shadowed --brdf phong:exponent=24,ks=0.5,kd=0.4 --bands 4 --samples 32 -q \
  -o "$dir/glossy.prt"

# --window none: the viewer projects the lighting at the largest band count of its transfers (here the
# diffuse one's) and the auto window depends on the band count; the headless render projects at the
# glossy transfer's bands. Unwindowed, truncation commutes and the two must agree exactly.
check() {  # check NAME [--brdf SPEC]
  name="$1"
  shift
  xvfb-run -a -s "-screen 0 1024x768x24" "$prt" view "$dir/mesh.ply" "$dir/glossy.prt" "$dir/transfer.prt" \
    --env "$dir/env.exr" --size 160x120 --camera 30,20,auto --rotate 45,0,0 --window none --frames 3 --screenshot "$dir/$name.exr" "$@"
  "$prt" render "$dir/mesh.ply" "$dir/glossy.prt" --env "$dir/env.exr" --size 160x120 --camera 30,20,auto \
    --rotate 45,0,0 --window none -q -o "$dir/$name-headless.exr" "$@"
  "$prt" compare "$dir/$name.exr" "$dir/$name-headless.exr" | tee "$dir/$name.txt"
  awk '{ for (i = 1; i <= NF; ++i) if ($i ~ /^rel_rms=/) { split($i, kv, "="); found = 1; ok = (kv[2] + 0 < 1e-5) } }
       END { exit !(found && ok) }' "$dir/$name.txt"
}
check baked
check override --brdf ggx:roughness=0.3,f0=0.5,albedo=0.3
echo "viewer glossy smoke test passed"
