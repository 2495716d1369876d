#!/usr/bin/env bash
# Regenerates the compressed glTF test files in tests/data/gltf/ (tests/data/README.md says what they
# are for): Debian's assimp-testmodels BoxTextured.glb compressed with Draco and with meshopt by
# gltf-transform, and each compressed file decoded back to plain glTF by gltf-transform ("copy"
# decodes both extensions), the independent truth that prt's decoders must match byte for byte.
#
# Needs node/npm and the Debian package assimp-testmodels. The npm packages go to a scratch folder
# (PRT_NPM_DIR, default /tmp/prt-gltf-transform), not into the repository.
set -euo pipefail
cd "$(dirname "$0")/.."

source_model=/usr/share/assimp/models/glTF2/BoxTextured-glTF-Binary/BoxTextured.glb
[[ -f "$source_model" ]] || { echo "make_compressed_gltf.sh: $source_model missing (apt-get install assimp-testmodels)" >&2; exit 1; }
npm_dir=${PRT_NPM_DIR:-/tmp/prt-gltf-transform}
mkdir -p "$npm_dir"
if [[ ! -x "$npm_dir/node_modules/.bin/gltf-transform" ]]; then
  (cd "$npm_dir" && npm init -y >/dev/null &&
    npm install --no-audit --no-fund @gltf-transform/cli@4.5.1 draco3dgltf@1.5.7 meshoptimizer@1.3.0 >/dev/null)
fi
gltf_transform="$npm_dir/node_modules/.bin/gltf-transform"

out=tests/data/gltf
mkdir -p "$out"
"$gltf_transform" draco "$source_model" "$out/box_textured_draco.glb"
"$gltf_transform" meshopt "$source_model" "$out/box_textured_meshopt.glb"
"$gltf_transform" copy "$out/box_textured_draco.glb" "$out/box_textured_draco_decoded.glb"
"$gltf_transform" copy "$out/box_textured_meshopt.glb" "$out/box_textured_meshopt_decoded.glb"
