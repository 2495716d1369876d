// `prt unwrap`'s glTF (docs/formats.md, "Unwrapped mesh") as engines' own code sees it: the Khronos glTF
// validator reports no errors and no warnings; three.js's GLTFLoader (the three of package-lock.json)
// loads it and the source with the same nodes (names included), materials and textures, the same meshes
// drawn at the same world matrices with the same world bounding boxes (1e-6 of the box's size) and the
// source's triangles less the degenerate ones, and every drawn mesh of the unwrapped file carries TEXCOORD_1 (three's uv1)
// inside [0, 1].
// Usage: node test_unwrap_gltf.mjs --out OUT.glb --source SOURCE.glb
import { readFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { Checker, argument } from './common.mjs';

const require = createRequire(import.meta.url);
const validator = require('gltf-validator');
globalThis.self = globalThis;
globalThis.createImageBitmap = async () => ({ width: 1, height: 1, close() {} });
globalThis.ProgressEvent ??= class extends Event { constructor(type, init = {}) { super(type); Object.assign(this, init); } };
const THREE = await import('three');
const { GLTFLoader } = await import('three/examples/jsm/loaders/GLTFLoader.js');
const check = new Checker('engines_unwrap_gltf');

async function load(path) {
  const b = readFileSync(path);
  const gltf = await new GLTFLoader().parseAsync(b.buffer.slice(b.byteOffset, b.byteOffset + b.length), '');
  const meshes = [];
  gltf.scene.updateMatrixWorld(true);
  gltf.scene.traverse((o) => { if (o.isMesh) meshes.push(o); });
  return { gltf, meshes, bytes: b };
}

// Triangles of a mesh; with `proper`, only those with three distinct vertices and a non-zero area (the
// cross product of two edges, in double, not 0): the loader skips the others (docs/formats.md).
function triangles(mesh, proper = false) {
  const g = mesh.geometry, p = g.attributes.position, n = (g.index ? g.index.count : p.count) / 3;
  if (!proper) return n;
  let count = 0;
  for (let t = 0; t < n; t++) {
    const [a, b, c] = [0, 1, 2].map((k) => (g.index ? g.index.getX(3 * t + k) : 3 * t + k));
    if (a === b || b === c || a === c) continue;
    const v = [a, b, c].map((i) => [p.getX(i), p.getY(i), p.getZ(i)]);
    const e = [0, 1, 2].map((k) => v[1][k] - v[0][k]), f = [0, 1, 2].map((k) => v[2][k] - v[0][k]);
    const cross = [e[1] * f[2] - e[2] * f[1], e[2] * f[0] - e[0] * f[2], e[0] * f[1] - e[1] * f[0]];
    if (cross.some((x) => x !== 0)) count++;
  }
  return count;
}

const out = argument('out'), source = argument('source');
const [a, b] = [await load(out), await load(source)];
const report = await validator.validateBytes(new Uint8Array(a.bytes), { uri: out, maxIssues: 200 });
const issues = report.issues.messages.filter((m) => m.severity <= 1).slice(0, 5).map((m) => `${m.code} ${m.pointer || ''} ${m.message}`);
check.check(`${out}: no validator errors or warnings`, report.issues.numErrors === 0 && report.issues.numWarnings === 0, issues.join('; '));
const [ja, jb] = [a.gltf.parser.json, b.gltf.parser.json];
for (const key of ['nodes', 'materials', 'textures', 'images', 'scenes'])
  check.check(`${out}: ${key} as in the source`, (ja[key] || []).length === (jb[key] || []).length);
(jb.nodes || []).forEach((node, i) => check.check(`${out}: node ${i}'s name as in the source`, ((ja.nodes || [])[i] || {}).name === node.name));
check.check(`${out}: as many meshes drawn as in the source`, a.meshes.length === b.meshes.length, `${a.meshes.length} vs ${b.meshes.length}`);
let total = [0, 0];
a.meshes.forEach((mesh, i) => {
  const other = b.meshes[i];
  if (!other) return;
  check.check(`${out}: mesh ${i} world matrix as in the source`,
              mesh.matrixWorld.elements.every((x, k) => Math.abs(x - other.matrixWorld.elements[k]) <= 1e-6 * (1 + Math.abs(x))));
  const [ba, bb] = [new THREE.Box3().setFromObject(mesh), new THREE.Box3().setFromObject(other)];
  const size = bb.getSize(new THREE.Vector3()).length();
  check.check(`${out}: mesh ${i} world box as in the source`,
              ba.min.distanceTo(bb.min) <= 1e-6 * size && ba.max.distanceTo(bb.max) <= 1e-6 * size);
  const [mine, theirs] = [triangles(mesh), triangles(other, true)];
  check.check(`${out}: mesh ${i} has the source's proper triangles`, mine === theirs, `${mine} vs ${theirs}`);
  total[0] += mine, total[1] += theirs;
  const uv = mesh.geometry.attributes.uv1;
  check.check(`${out}: mesh ${i} has TEXCOORD_1 in [0, 1]`, !!uv && Array.from(uv.array).every((v) => v >= 0 && v <= 1));
});
console.log(`${out}: ${report.issues.numErrors} errors, ${report.issues.numWarnings} warnings; ${a.meshes.length} meshes drawn, ${total[0]} triangles (source ${total[1]} proper)`);
check.finish();
