#!/usr/bin/env bash
# What a base colour texture costs a bake (issue 33, docs/performance.md "Textured bakes"): an open box of
# 16,000 triangles (5 faces of 40 x 40 quads) with a random 1024^2 8-bit PNG, against the same box with
# the texture left out (Kd 0.9 0.7 0.5, so both bake 3 channels). Interreflected, 3 bands, 256 rays,
# 2 threads; the bounce time is the 2-bounce bake minus the 0-bounce bake. Runs alternate, ROUNDS of
# each; every line gives wall and user CPU seconds.
# Usage: scripts/bench_textured_bake.sh [PRT] [ROUNDS] [OUT_DIR]   (default build/src/cli/prt, 3, out/textured_bake)
set -euo pipefail
cd "$(dirname "$0")/.."
prt=${1:-build/src/cli/prt}
rounds=${2:-3}
out=${3:-out/textured_bake}
mkdir -p "$out"
python3 - "$out" <<'EOF'
import random, struct, sys, zlib
out = sys.argv[1]
random.seed(1)
size = 1024
rows = b"".join(b"\0" + bytes(random.getrandbits(8) for _ in range(3 * size)) for _ in range(size))
def chunk(tag, data):
    return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data) & 0xffffffff)
with open(out + "/tex.png", "wb") as f:
    f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", size, size, 8, 2, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(rows, 6)) + chunk(b"IEND", b""))
n = 40
vertices, uvs, faces = [], [], []
def face(origin, a, b, uv0):
    base = len(vertices)
    for j in range(n + 1):
        for i in range(n + 1):
            vertices.append([origin[k] + a[k] * i / n + b[k] * j / n for k in range(3)])
            uvs.append((uv0[0] + 0.5 * i / n, uv0[1] + 0.33 * j / n))
    for j in range(n):
        for i in range(n):
            v = base + j * (n + 1) + i
            faces.extend([(v, v + 1, v + n + 2), (v, v + n + 2, v + n + 1)])
face((-1, 0, 1), (2, 0, 0), (0, 0, -2), (0, 0))
face((-1, 0, -1), (2, 0, 0), (0, 2, 0), (0.5, 0))
face((1, 0, 1), (-2, 0, 0), (0, 2, 0), (0, 0.33))
face((-1, 0, 1), (0, 0, -2), (0, 2, 0), (0.5, 0.33))
face((1, 0, -1), (0, 0, 2), (0, 2, 0), (0, 0.66))
for name, textured in (("tex", True), ("plain", False)):
    with open(f"{out}/{name}.obj", "w") as f:
        f.write(f"mtllib {name}.mtl\n")
        f.writelines("v %g %g %g\n" % tuple(p) for p in vertices)
        f.writelines("vt %g %g\n" % uv for uv in uvs)
        f.write("usemtl m\n")
        f.writelines("f %d/%d %d/%d %d/%d\n" % (a + 1, a + 1, b + 1, b + 1, c + 1, c + 1) for a, b, c in faces)
    with open(f"{out}/{name}.mtl", "w") as f:
        f.write("newmtl m\nKd 0.9 0.7 0.5\n" + ("map_Kd tex.png\n" if textured else ""))
EOF
for round in $(seq "$rounds"); do
  for mesh in plain tex; do
    for bounces in 2 0; do
      /usr/bin/time -f "$mesh bounces $bounces: %e s wall, %U s user (round $round)" "$prt" bake "$out/$mesh.obj" \
        --transfer interreflected --bands 3 --samples 256 --bounces "$bounces" --threads 2 -q -o "$out/$mesh$bounces.prt"
    done
  done
done
