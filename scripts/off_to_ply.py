#!/usr/bin/env python3
"""Converts an OFF triangle mesh to the binary little-endian PLY prt ships in assets/meshes/.

Steps, in order: optional rotation about +Y (degrees, right-handed: to turn a model to face +Z),
centring (bounding-box centre to the origin), scaling (largest distance from the centre to 1),
fan triangulation of polygons, and a winding check: the signed volume must be positive (outward,
counter-clockwise faces); if it is negative every face is reversed. Each undirected edge should be
used once in each direction by a consistently oriented closed mesh; the script reports edges that
are not, and refuses meshes whose orientation is inconsistent.

Output: "element vertex" with float x, y, z and "element face" with list uchar int vertex_indices;
vertices keep the OFF order. Pure Python (no numpy), deterministic.

    scripts/off_to_ply.py IN.off OUT.ply [--rotate-y DEG] [--comment TEXT]...
"""
import argparse
import math
import struct
import sys


def read_off(path):
    tokens = []
    with open(path) as f:
        for line in f:
            line = line.split("#", 1)[0].strip()
            if line:
                tokens.extend(line.split())
    header = tokens[0]
    if header not in ("OFF", "COFF", "NOFF"):
        sys.exit(f"{path}: not an OFF file (starts with {header!r})")
    n_vertices, n_faces = int(tokens[1]), int(tokens[2])
    stride = 3 + (4 if header == "COFF" else 0) + (3 if header == "NOFF" else 0)
    i = 4
    vertices = []
    for _ in range(n_vertices):
        vertices.append([float(t) for t in tokens[i:i + 3]])
        i += stride
    faces = []
    for _ in range(n_faces):
        n = int(tokens[i])
        polygon = [int(t) for t in tokens[i + 1:i + 1 + n]]
        i += 1 + n
        for j in range(1, n - 1):  # fan triangulation
            faces.append([polygon[0], polygon[j], polygon[j + 1]])
    return vertices, faces


def signed_volume(vertices, faces):
    volume = 0.0
    for a, b, c in faces:
        (ax, ay, az), (bx, by, bz), (cx, cy, cz) = vertices[a], vertices[b], vertices[c]
        volume += (ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx) + az * (bx * cy - by * cx)) / 6.0
    return volume


def edge_report(faces):
    directed = {}
    for f in faces:
        for k in range(3):
            edge = (f[k], f[(k + 1) % 3])
            directed[edge] = directed.get(edge, 0) + 1
    repeated = sum(1 for count in directed.values() if count > 1)  # same direction twice: flipped face
    boundary = sum(1 for (a, b) in directed if (b, a) not in directed)
    return repeated, boundary


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("input")
    parser.add_argument("output")
    parser.add_argument("--rotate-y", type=float, default=0.0, help="rotation about +Y in degrees")
    parser.add_argument("--comment", action="append", default=[], help="PLY header comment (repeatable)")
    args = parser.parse_args()

    vertices, faces = read_off(args.input)
    angle = math.radians(args.rotate_y)
    cos_a, sin_a = math.cos(angle), math.sin(angle)
    vertices = [[cos_a * x + sin_a * z, y, -sin_a * x + cos_a * z] for x, y, z in vertices]
    lo = [min(v[k] for v in vertices) for k in range(3)]
    hi = [max(v[k] for v in vertices) for k in range(3)]
    centre = [(lo[k] + hi[k]) / 2 for k in range(3)]
    vertices = [[v[k] - centre[k] for k in range(3)] for v in vertices]
    radius = max(math.sqrt(sum(c * c for c in v)) for v in vertices)
    vertices = [[c / radius for c in v] for v in vertices]

    volume = signed_volume(vertices, faces)
    flipped = volume < 0
    if flipped:
        faces = [[a, c, b] for a, b, c in faces]
        volume = -volume
    repeated, boundary = edge_report(faces)
    if repeated:
        sys.exit(f"{args.input}: {repeated} directed edges are used twice: inconsistent face orientation")
    degenerate = sum(1 for a, b, c in faces if a == b or b == c or a == c)
    unused = len(vertices) - len({i for f in faces for i in f})

    header = ["ply", "format binary_little_endian 1.0"]
    header += [f"comment {c}" for c in args.comment]
    header += [f"element vertex {len(vertices)}", "property float x", "property float y", "property float z",
               f"element face {len(faces)}", "property list uchar int vertex_indices", "end_header"]
    with open(args.output, "wb") as out:
        out.write(("\n".join(header) + "\n").encode("ascii"))
        out.write(b"".join(struct.pack("<3f", *v) for v in vertices))
        out.write(b"".join(struct.pack("<B3i", 3, *f) for f in faces))

    lo = [min(v[k] for v in vertices) for k in range(3)]
    hi = [max(v[k] for v in vertices) for k in range(3)]
    print(f"{args.output}: {len(vertices)} vertices, {len(faces)} triangles, signed volume {volume:.6f}"
          f"{' (faces reversed)' if flipped else ''}, boundary edges {boundary}, degenerate {degenerate}, "
          f"unused vertices {unused}, bounds {[round(c, 4) for c in lo]} .. {[round(c, 4) for c in hi]}")


if __name__ == "__main__":
    main()
