#!/bin/sh
# GLFW smoke test for `prt view` (run by ctest): opens the viewer under a virtual X server, draws a few
# frames with two transfers and two environments loaded, saves screenshots (PNG and EXR), exits 0; then
# checks the EXR screenshot against `prt render` of the same view (same renderer, same camera).
# Usage: viewer_smoke.sh PRT MAKE_FIXTURES. Fails (exit 1) if xvfb-run is not installed:
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

view() {
  xvfb-run -a -s "-screen 0 1024x768x24" "$prt" view "$dir/mesh.ply" "$dir/transfer.prt" "$dir/transfer_grey.prt" \
    --env "$dir/env.exr" --env "$dir/light.json" --size 160x120 --camera 30,20,auto --rotate 45,0,0 "$@"
}
view --frames 5 --screenshot "$dir/shot.png"
view --frames 3 --screenshot "$dir/shot.exr"
test -s "$dir/shot.png"
test -s "$dir/shot.exr"

"$prt" render "$dir/mesh.ply" "$dir/transfer.prt" --env "$dir/env.exr" --size 160x120 --camera 30,20,auto \
  --rotate 45,0,0 -q -o "$dir/headless.exr"
"$prt" compare "$dir/shot.exr" "$dir/headless.exr" | tee "$dir/compare.txt"
# The window and headless paths run the same renderer: the images agree to float rounding.
# `prt compare` prints one line "rms=... rel_rms=... max_abs=... max_rel=... pixels=...".
awk '{ for (i = 1; i <= NF; ++i) if ($i ~ /^rel_rms=/) { split($i, kv, "="); found = 1; ok = (kv[2] + 0 < 1e-5) } }
     END { exit !(found && ok) }' "$dir/compare.txt"
echo "viewer smoke test passed"
