// The engine glTF of `prt bake --gltf` (docs/formats.md, "The engine glTF: PRT_transfer") as engines'
// own code sees it: the Khronos glTF validator reports 0 errors (PRT_transfer is an unknown extension:
// infos only); three.js's GLTFLoader (the three of package-lock.json) loads the export and the source
// with the same node, material and texture counts, the same meshes at the same world matrices, and every
// primitive of the export with at most 16 vertex attributes (WebGL2's MAX_VERTEX_ATTRIBS), its
// _PRT_CLUSTER values integers in [0, K) and its weights attributes as many as the model's terms need.
// Usage: node test_engine_gltf.mjs --pairs OUT.glb=SOURCE.glb[,OUT2.glb=SOURCE2.glb...]
import { readFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { Checker, argument } from './common.mjs';

const require = createRequire(import.meta.url);
const validator = require('gltf-validator');
// GLTFLoader decodes images with createImageBitmap; node has none, and this test does not need pixels.
globalThis.self = globalThis;
globalThis.createImageBitmap = async () => ({ width: 1, height: 1, close() {} });
const { GLTFLoader } = await import('three/examples/jsm/loaders/GLTFLoader.js');
const check = new Checker('engines_engine_gltf');

async function load(path) {
  const b = readFileSync(path);
  return new GLTFLoader().parseAsync(b.buffer.slice(b.byteOffset, b.byteOffset + b.length), '');
}

async function summary(gltf) {
  const meshes = [];
  gltf.scene.updateMatrixWorld(true);
  gltf.scene.traverse((o) => { if (o.isMesh) meshes.push(o); });
  return {
    nodes: gltf.parser.json.nodes.length,
    materials: (await gltf.parser.getDependencies('material')).length,
    textures: (await gltf.parser.getDependencies('texture')).length,
    meshes,
  };
}

async function checkPair(out, source) {
  const bytes = readFileSync(out);
  const report = await validator.validateBytes(new Uint8Array(bytes), { uri: out, maxIssues: 200 });
  check.check(`${out}: 0 validator errors`, report.issues.numErrors === 0,
              report.issues.messages.filter((m) => m.severity === 0).slice(0, 5).map((m) => `${m.code} ${m.pointer || ''} ${m.message}`).join('; '));
  console.log(`${out}: ${report.issues.numErrors} errors, ${report.issues.numWarnings} warnings, ${report.issues.numInfos} infos`);

  const [a, b] = [await load(out), await load(source)];
  const [s, t] = [await summary(a), await summary(b)];
  for (const key of ['nodes', 'materials', 'textures'])
    check.check(`${out}: ${key} as in the source`, s[key] === t[key], `${s[key]} vs ${t[key]}`);
  check.check(`${out}: as many meshes drawn as in the source`, s.meshes.length === t.meshes.length, `${s.meshes.length} vs ${t.meshes.length}`);
  const model = a.parser.json.extensions.PRT_transfer.models[0];
  s.meshes.forEach((mesh, i) => {
    const other = t.meshes[i];
    if (!other) return;
    check.check(`${out}: mesh ${i} world matrix as in the source`,
                mesh.matrixWorld.elements.every((x, k) => Math.abs(x - other.matrixWorld.elements[k]) <= 1e-6 * (1 + Math.abs(x))));
    check.check(`${out}: mesh ${i} vertex count as in the source`,
                mesh.geometry.attributes.position.count === other.geometry.attributes.position.count);
    const names = Object.keys(mesh.geometry.attributes);
    check.check(`${out}: mesh ${i} has at most 16 attributes`, names.length <= 16, names.join(' '));
    const cluster = mesh.geometry.attributes._prt_cluster;
    check.check(`${out}: mesh ${i} has _PRT_CLUSTER`, !!cluster);
    if (cluster)
      check.check(`${out}: mesh ${i} cluster indices are integers in [0, K)`,
                  Array.from(cluster.array).every((k) => Number.isInteger(k) && k >= 0 && k < model.clusters));
    const weights = names.filter((n) => n.startsWith('_prt_weights')).length;
    check.check(`${out}: mesh ${i} has ceil(N / 4) weight attributes`, weights === Math.ceil(model.terms / 4), `${weights}`);
    check.check(`${out}: mesh ${i} has _PRT_ALBEDO`, !!mesh.geometry.attributes._prt_albedo);
  });
}

for (const pair of argument('pairs').split(',').filter(Boolean)) {
  const [out, source] = pair.split('=');
  await checkPair(out, source);
}
check.finish();
