// A lightmap test scene as OBJ with lightmap UVs (vt): a 4 x 4 floor at y = 0 and, on it, an open box
// (its +X face, top and +Z face), each quad a chart of its own in a 2 x 2 atlas with a 1/16 margin;
// material Kd 0.8 (the albedo of the bake and of the sun's direct light).
import { writeFileSync } from 'node:fs';
import { join } from 'node:path';

export function writeLightmapScene(folder) {
  const v = [], vt = [], f = [];
  const quad = (corner, u, w, n, chart) => {
    const base = v.length;
    const [cx, cy] = [chart % 2, Math.floor(chart / 2)];
    for (let j = 0; j <= n; j++) {
      for (let i = 0; i <= n; i++) {
        v.push([0, 1, 2].map((k) => corner[k] + (u[k] * i) / n + (w[k] * j) / n));
        vt.push([0.5 * cx + 1 / 16 + (0.5 - 1 / 8) * (i / n), 0.5 * cy + 1 / 16 + (0.5 - 1 / 8) * (j / n)]);
      }
    }
    for (let j = 0; j < n; j++) {
      for (let i = 0; i < n; i++) {
        const a = base + j * (n + 1) + i + 1, b = a + 1, c = a + n + 1, d = c + 1;
        f.push([a, b, d], [a, d, c]);
      }
    }
  };
  quad([-2, 0, -2], [0, 0, 4], [4, 0, 0], 8, 0);
  quad([0.5, 0.001, -0.5], [0, 1, 0], [0, 0, 1], 4, 1);
  quad([-0.5, 1, -0.5], [0, 0, 1], [1, 0, 0], 4, 2);
  quad([-0.5, 0.001, 0.5], [1, 0, 0], [0, 1, 0], 4, 3);
  writeFileSync(join(folder, 'lightmap.mtl'), 'newmtl grey\nKd 0.8 0.8 0.8\n');
  const lines = ['mtllib lightmap.mtl', 'usemtl grey', ...v.map((p) => `v ${p.join(' ')}`), ...vt.map((t) => `vt ${t.join(' ')}`),
                 ...f.map((t) => `f ${t.map((i) => `${i}/${i}`).join(' ')}`)];
  writeFileSync(join(folder, 'lightmap.obj'), lines.join('\n') + '\n');
  return join(folder, 'lightmap.obj');
}

// A mixed scene (prt bake --texel-parts) as a glTF with one node, mesh and primitive per part, all of one
// material (baseColorFactor 0.8): "Floor" (4 x 4 at y = 0) and "Wall" (a back wall at z = -2, facing +z),
// baked per texel (TEXCOORD_0: the floor in [1/16, 7/16] x [1/16, 15/16], the wall in [9/16, 15/16] x
// [1/16, 7/16]), and "Box", the open box of writeLightmapScene standing on the floor, per vertex (its
// UVs the atlas's last quarter, where they could be baked per texel too). Returns the .gltf's path.
export function writeMixedScene(folder) {
  const parts = [];
  const part = (name, quads) => {
    const p = { name, v: [], n: [], uv: [], f: [] };
    for (const [corner, u, w, steps, uv0, uv1] of quads) {
      const base = p.v.length / 3, normal = cross(u, w);
      for (let j = 0; j <= steps; j++) {
        for (let i = 0; i <= steps; i++) {
          p.v.push(...[0, 1, 2].map((k) => corner[k] + (u[k] * i) / steps + (w[k] * j) / steps));
          p.n.push(...normal);
          p.uv.push(uv0[0] + (uv1[0] - uv0[0]) * (i / steps), uv0[1] + (uv1[1] - uv0[1]) * (j / steps));
        }
      }
      for (let j = 0; j < steps; j++) {
        for (let i = 0; i < steps; i++) {
          const a = base + j * (steps + 1) + i, b = a + 1, c = a + steps + 1, d = c + 1;
          p.f.push(a, b, d, a, d, c);
        }
      }
    }
    parts.push(p);
  };
  part('Floor', [[[-2, 0, -2], [0, 0, 4], [4, 0, 0], 8, [1 / 16, 1 / 16], [7 / 16, 15 / 16]]]);
  part('Wall', [[[-2, 0, -2], [4, 0, 0], [0, 1.5, 0], 4, [9 / 16, 1 / 16], [15 / 16, 7 / 16]]]);
  part('Box', [[[0.5, 0.001, -0.5], [0, 1, 0], [0, 0, 1], 4, [9 / 16, 9 / 16], [11 / 16, 11 / 16]],
               [[-0.5, 1, -0.5], [0, 0, 1], [1, 0, 0], 4, [12 / 16, 9 / 16], [14 / 16, 11 / 16]],
               [[-0.5, 0.001, 0.5], [1, 0, 0], [0, 1, 0], 4, [9 / 16, 12 / 16], [11 / 16, 14 / 16]]]);
  const chunks = [], views = [], accessors = [];
  let length = 0;
  const add = (array, target, type, componentType, extra = {}) => {
    const bytes = Buffer.from(array.buffer, array.byteOffset, array.byteLength);
    chunks.push(bytes, Buffer.alloc((4 - (bytes.length % 4)) % 4));
    views.push({ buffer: 0, byteOffset: length, byteLength: bytes.length, target });
    length += bytes.length + ((4 - (bytes.length % 4)) % 4);
    const width = { SCALAR: 1, VEC2: 2, VEC3: 3 }[type];
    accessors.push({ bufferView: views.length - 1, componentType, count: array.length / width, type, ...extra });
    return accessors.length - 1;
  };
  const meshes = parts.map((p) => {
    const lo = [0, 1, 2].map((k) => Math.min(...p.v.filter((_, i) => i % 3 === k)));
    const hi = [0, 1, 2].map((k) => Math.max(...p.v.filter((_, i) => i % 3 === k)));
    const attributes = {
      POSITION: add(new Float32Array(p.v), 34962, 'VEC3', 5126, { min: lo, max: hi }),
      NORMAL: add(new Float32Array(p.n), 34962, 'VEC3', 5126),
      TEXCOORD_0: add(new Float32Array(p.uv), 34962, 'VEC2', 5126),
    };
    return { name: p.name, primitives: [{ attributes, indices: add(new Uint16Array(p.f), 34963, 'SCALAR', 5123), material: 0, mode: 4 }] };
  });
  const bin = Buffer.concat(chunks);
  const doc = {
    asset: { version: '2.0', generator: 'prt web/test/lightmap_scene.mjs' }, scene: 0, scenes: [{ nodes: parts.map((_, i) => i) }],
    nodes: parts.map((p, i) => ({ name: p.name, mesh: i })), meshes,
    materials: [{ name: 'grey', pbrMetallicRoughness: { baseColorFactor: [0.8, 0.8, 0.8, 1], metallicFactor: 0, roughnessFactor: 1 } }],
    buffers: [{ byteLength: bin.length, uri: 'mixed_room.bin' }], bufferViews: views, accessors,
  };
  writeFileSync(join(folder, 'mixed_room.bin'), bin);
  writeFileSync(join(folder, 'mixed_room.gltf'), JSON.stringify(doc));
  return join(folder, 'mixed_room.gltf');
}

function cross(a, b) {
  const c = [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
  const n = Math.hypot(...c);
  return c.map((x) => x / n);
}
