#!/usr/bin/env bash
# Size and shaded error of the engine glTF (docs/formats.md, "The engine glTF: PRT_transfer") against the
# float32 .prt of the same bake (issue 34: per-vertex RGB 5-band at the default export settings at most
# 1/2 of the .prt payload, its shaded error stated). Bakes MESH (default: Khronos's 2CylinderEngine from
# Debian's assimp-testmodels, RGB materials) per vertex, interreflected, 5 bands, writes the .prt and the
# .glb in one run, then shades both under each HDRI with `prt shade` (sun split off as a disc, exact) and
# reports prt compare's rel_rms of the .glb's radiance against the .prt's.
# Usage: bench/engine_gltf_size.sh [MESH] [SAMPLES]   (prt from build/src/cli/prt)
set -euo pipefail
cd "$(dirname "$0")/.."
prt=build/src/cli/prt
mesh=${1:-/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb}
samples=${2:-128}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
start=$(date +%s.%N)
"$prt" bake "$mesh" --transfer interreflected --bands 5 --samples "$samples" --bounces 2 -q -o "$work/t.prt" --gltf "$work/t.glb"
echo "bake + export: $(echo "$(date +%s.%N) - $start" | bc) s"
python3 - "$work/t.prt" "$work/t.glb" <<'EOF'
import json, os, struct, sys
prt, glb = sys.argv[1], sys.argv[2]
b = open(glb, 'rb').read()
n = struct.unpack('<I', b[12:16])[0]
d = json.loads(b[20:20 + n])
views, acc = d['bufferViews'], d['accessors']
model = d['extensions']['PRT_transfer']['models'][0]
size = lambda a: views[acc[a]['bufferView']]['byteLength']
prims = [p for m in d['meshes'] for p in m['primitives'] if 'PRT_transfer' in p.get('extensions', {})]
vertices = sum(acc[p['attributes']['POSITION']]['count'] for p in prims)
attributes = sum(size(a) for p in prims for k, a in p['attributes'].items() if k.startswith('_PRT_'))
model_bytes = size(model['means']) + size(model['bases'])
C, B = model['channels'], model['bands']
D = C * B * B
payload = vertices * D * 4 * (2 if model['bounce'] else 1)
print(f"vertices {vertices}, RGB {B} bands, K={model['clusters']} N={model['terms']}, bounce part {model['bounce']}")
print(f".prt file {os.path.getsize(prt)} B; float32 payload {payload} B = {payload / vertices:.1f} B/vertex "
      f"({D * 4} B/vertex without the bounce part)")
print(f".glb file {len(b)} B; transfer in it: attributes {attributes} B + model {model_bytes} B = "
      f"{(attributes + model_bytes) / vertices:.1f} B/vertex")
print(f"ratio transfer/.prt payload {(attributes + model_bytes) / payload:.3f} "
      f"(against the payload without the bounce part {(attributes + model_bytes) / (vertices * D * 4):.3f})")
EOF
for env in sunrise city studio; do
  "$prt" shade "$work/t.glb" "$work/t.glb" --env "assets/env/$env.exr" -o "$work/g.ply" 2>/dev/null
  "$prt" shade "$mesh" "$work/t.prt" --env "assets/env/$env.exr" -o "$work/p.ply" 2>/dev/null
  echo "shaded error under $env.exr: $("$prt" compare "$work/g.ply" "$work/p.ply")"
done
