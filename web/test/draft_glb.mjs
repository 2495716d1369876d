// Test fixture, independent of prt's engine-glTF writer: builds a PRT_transfer glTF (docs/formats.md,
// "The engine glTF") from prt's plain mesh .glb (`prt bake --gltf` before the engine glTF: POSITION,
// NORMAL, indices, in prt's vertex order; its _PRT_T* attributes are dropped) and a per-vertex .cprt
// (docs/formats.md, "Compressed transfer files"), so that the runtime can be checked against
// `prt render MESH FILE.cprt` on a file no prt code wrote.
//
// Usage: node draft_glb.mjs MESH.glb TRANSFER.cprt ALBEDO_R,G,B OUT.glb
import { readFileSync, writeFileSync } from 'node:fs';

const KINDS = { 0: 'unshadowed', 1: 'shadowed', 2: 'interreflected' };

export function readGlb(buffer) {
  if (buffer.toString('ascii', 0, 4) !== 'glTF') throw new Error('not a GLB');
  const jsonLength = buffer.readUInt32LE(12);
  const json = JSON.parse(buffer.toString('utf8', 20, 20 + jsonLength));
  const binStart = 20 + jsonLength + 8;
  return { json, bin: buffer.subarray(binStart, binStart + buffer.readUInt32LE(20 + jsonLength)) };
}

function readCprt(buffer) {
  if (buffer.toString('latin1', 0, 8) !== 'PRTCPCA\0') throw new Error('not a .cprt');
  const u32 = (o) => buffer.readUInt32LE(o);
  const h = { version: u32(8), kind: u32(12), bands: u32(16), outBands: u32(20), channels: u32(24), scalar: u32(28),
              clusters: u32(32), terms: u32(36), flags: u32(44), vertices: Number(buffer.readBigUInt64LE(48)) };
  if (h.version !== 1 || h.outBands !== 0 || h.scalar !== 0) throw new Error('fixture reads per-vertex diffuse float32 .cprt only');
  const p = u32(120);
  const payload = Math.ceil((124 + p) / 8) * 8 + 8;
  const e = h.channels * h.bands * h.bands * (h.flags & 2 ? 2 : 1);
  const floats = (offset, count) => new Float32Array(buffer.buffer.slice(buffer.byteOffset + offset, buffer.byteOffset + offset + 4 * count));
  const means = floats(payload, h.clusters * e);
  const bases = floats(payload + 4 * means.length, h.clusters * h.terms * e);
  const weights = floats(payload + 4 * (means.length + bases.length), h.vertices * h.terms);
  const at = payload + 4 * (means.length + bases.length + weights.length);
  const ids = new Uint32Array(buffer.buffer.slice(buffer.byteOffset + at, buffer.byteOffset + at + 4 * h.vertices));
  return { ...h, e, means, bases, weights, ids };
}

export function draftGlb(meshGlb, cprt, albedo) {
  const { json, bin } = readGlb(meshGlb);
  const t = readCprt(cprt);
  const chunks = [];
  let length = 0;
  const add = (array) => { chunks.push(Buffer.from(array.buffer, array.byteOffset, array.byteLength)); const o = length; length += array.byteLength; return o; };
  const out = { asset: { version: '2.0', generator: 'prt web/test/draft_glb.mjs' }, scene: 0, scenes: [{ nodes: [0] }], nodes: [{ mesh: 0 }],
                buffers: [{}], bufferViews: [], accessors: [], extensionsUsed: ['PRT_transfer'] };
  const accessor = (array, type, count, extra = {}) => {
    out.bufferViews.push({ buffer: 0, byteOffset: add(array), byteLength: array.byteLength });
    out.accessors.push({ bufferView: out.bufferViews.length - 1, componentType: array instanceof Uint32Array ? 5125 : 5126, count, type, ...extra });
    return out.accessors.length - 1;
  };
  const source = (i) => {
    const a = json.accessors[i], v = json.bufferViews[a.bufferView];
    const size = { SCALAR: 1, VEC3: 3 }[a.type];
    const Type = a.componentType === 5125 ? Uint32Array : Float32Array;
    return new Type(bin.buffer.slice(bin.byteOffset + (v.byteOffset || 0) + (a.byteOffset || 0), bin.byteOffset + (v.byteOffset || 0) + (a.byteOffset || 0) + 4 * size * a.count));
  };
  const primitive = json.meshes[0].primitives[0];
  const positions = source(primitive.attributes.POSITION);
  const n = t.vertices;
  const lo = [0, 1, 2].map((k) => Math.min(...positions.filter((_, i) => i % 3 === k)));
  const hi = [0, 1, 2].map((k) => Math.max(...positions.filter((_, i) => i % 3 === k)));
  const attributes = { POSITION: accessor(positions, 'VEC3', n, { min: lo, max: hi }), NORMAL: accessor(source(primitive.attributes.NORMAL), 'VEC3', n),
                       _PRT_CLUSTER: accessor(Float32Array.from(t.ids), 'SCALAR', n),
                       _PRT_ALBEDO: accessor(Float32Array.from({ length: 3 * n }, (_, i) => albedo[i % 3]), 'VEC3', n) };
  for (let a = 0; a < Math.ceil(t.terms / 4); a++) {
    const w = new Float32Array(4 * n);
    for (let v = 0; v < n; v++) for (let c = 0; c < 4 && 4 * a + c < t.terms; c++) w[4 * v + c] = t.weights[v * t.terms + 4 * a + c];
    attributes[`_PRT_WEIGHTS${a}`] = accessor(w, 'VEC4', n);
  }
  const indices = source(primitive.indices);
  out.meshes = [{ primitives: [{ attributes, indices: accessor(indices, 'SCALAR', indices.length), mode: 4, material: 0, extensions: { PRT_transfer: { model: 0 } } }] }];
  out.materials = [{ pbrMetallicRoughness: { baseColorFactor: [...albedo, 1], metallicFactor: 0, roughnessFactor: 1 } }];
  out.extensions = { PRT_transfer: { version: 1, models: [{ kind: KINDS[t.kind], bands: t.bands, channels: t.channels, clusters: t.clusters,
    terms: t.terms, bounce: !!(t.flags & 2), means: accessor(t.means, 'SCALAR', t.means.length), bases: accessor(t.bases, 'SCALAR', t.bases.length),
    layout: 'fixture' }] } };
  out.buffers[0].byteLength = length;
  const body = Buffer.concat(chunks);
  const jsonText = Buffer.from(JSON.stringify(out));
  const jsonChunk = Buffer.concat([jsonText, Buffer.alloc((4 - (jsonText.length % 4)) % 4, 0x20)]);
  const binChunk = Buffer.concat([body, Buffer.alloc((4 - (body.length % 4)) % 4)]);
  const header = Buffer.alloc(12);
  header.write('glTF', 0);
  header.writeUInt32LE(2, 4);
  header.writeUInt32LE(12 + 8 + jsonChunk.length + 8 + binChunk.length, 8);
  const chunkHeader = (len, type) => { const b = Buffer.alloc(8); b.writeUInt32LE(len, 0); b.write(type, 4); return b; };
  return Buffer.concat([header, chunkHeader(jsonChunk.length, 'JSON'), jsonChunk, chunkHeader(binChunk.length, 'BIN\0'), binChunk]);
}

if (process.argv[1] && process.argv[1].endsWith('draft_glb.mjs')) {
  const [mesh, cprt, albedo, output] = process.argv.slice(2);
  writeFileSync(output, draftGlb(readFileSync(mesh), readFileSync(cprt), albedo.split(',').map(Number)));
}
