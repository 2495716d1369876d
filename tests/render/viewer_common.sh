# Sourced by the viewer smoke tests: fails without xvfb-run (scripts/setup.sh --tests installs it, so a
# missing one is a broken setup, not a reason to skip), then makes the
# fixture folder $dir (removed on exit) and fills it with make_render_fixtures ($1 of the caller: $make_fixtures).
if ! command -v xvfb-run >/dev/null 2>&1; then
  echo "FAILED: xvfb-run is not installed (scripts/setup.sh --tests installs xvfb); the viewer needs an X display"
  exit 1
fi
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
"$make_fixtures" "$dir"
# rel_rms_between FILE LO HI: the `prt compare` line in FILE has LO <= rel_rms < HI (exit status).
rel_rms_between() {
  awk -v lo="$2" -v hi="$3" '{ for (i = 1; i <= NF; ++i) if ($i ~ /^rel_rms=/) { split($i, kv, "="); found = 1; ok = (kv[2] + 0 >= lo && kv[2] + 0 < hi) } }
       END { exit !(found && ok) }' "$1"
}
