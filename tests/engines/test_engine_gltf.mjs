// The engine glTF of `prt bake --gltf` (docs/formats.md, "The engine glTF: PRT_transfer") as engines'
// own code sees it: the Khronos glTF validator reports 0 errors (PRT_transfer is an unknown extension:
// infos only); three.js's GLTFLoader (the three of package-lock.json) loads the export and the source
// with the same node, material and texture counts, the same meshes at the same world matrices, and every
// primitive of the export with at most 16 vertex attributes (WebGL2's MAX_VERTEX_ATTRIBS), its
// _PRT_CLUSTER values integers in [0, K) and its weights attributes as many as the model's terms need.
// A per-texel export (prt bake --lightmap --gltf) carries one vertex attribute, _PRT_ALBEDO (values in
// [0, 1]: the discs' direct light's albedo), and KTX2 textures; a mixed scene's (--texel-parts) has both
// kinds of primitive, each checked against the model it names. The textures are read
// here with ktx-parse: RGBA16F of the stated size, the cluster texture's R an integer in [0, K) and G a
// coverage code (0, 1, 2), the weights texture an array of ceil(N / 4) layers; the validator's only
// warnings are about the KTX2 images it does not know (it predates KHR_texture_basisu).
// Usage: node test_engine_gltf.mjs --pairs OUT.glb=SOURCE.glb[,OUT2.glb=SOURCE2.glb...]
import { readFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { dirname, join } from 'node:path';
import { read as readKtx } from 'ktx-parse';
import { Checker, argument } from './common.mjs';

const require = createRequire(import.meta.url);
const validator = require('gltf-validator');
// GLTFLoader decodes images with createImageBitmap; node has none, and this test does not need pixels.
globalThis.self = globalThis;
globalThis.createImageBitmap = async () => ({ width: 1, height: 1, close() {} });
globalThis.ProgressEvent ??= class extends Event { constructor(type, init = {}) { super(type); Object.assign(this, init); } };
const { GLTFLoader } = await import('three/examples/jsm/loaders/GLTFLoader.js');
const check = new Checker('engines_engine_gltf');

// A .glb, or a .gltf with its external buffers and images inlined as data: URIs (node has no file URLs for three).
async function load(path) {
  const b = readFileSync(path);
  if (!path.endsWith('.gltf')) return new GLTFLoader().parseAsync(b.buffer.slice(b.byteOffset, b.byteOffset + b.length), '');
  const doc = JSON.parse(b.toString('utf8'));
  for (const list of ['buffers', 'images'])
    for (const item of doc[list] || [])
      if (item.uri && !item.uri.startsWith('data:'))
        item.uri = `data:application/octet-stream;base64,${readFileSync(join(dirname(path), decodeURIComponent(item.uri))).toString('base64')}`;
  return new GLTFLoader().parseAsync(JSON.stringify(doc), '');
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

// IEEE binary16 to a number.
function half(bits) {
  const sign = bits & 0x8000 ? -1 : 1, exponent = (bits >> 10) & 0x1f, fraction = bits & 0x3ff;
  if (exponent === 0) return sign * fraction * 2 ** -24;
  if (exponent === 31) return fraction ? NaN : sign * Infinity;
  return sign * (1 + fraction / 1024) * 2 ** (exponent - 15);
}

// The texel textures of the per-texel primitives of an export, by the GLB layout and formats.md.
function checkTexels(out, bytes, models) {
  const jsonLength = bytes.readUInt32LE(12);
  const doc = JSON.parse(bytes.toString('utf8', 20, 20 + jsonLength));
  const bin = bytes.subarray(20 + jsonLength + 8);
  const ktx = (image) => {
    const view = doc.bufferViews[doc.images[image].bufferView];
    return readKtx(new Uint8Array(bin.buffer, bin.byteOffset + (view.byteOffset || 0), view.byteLength));
  };
  for (const mesh of doc.meshes)
    for (const p of mesh.primitives) {
      const ext = p.extensions.PRT_transfer;
      if (!('width' in ext)) continue;  // a mixed scene's per-vertex primitive
      const model = models[ext.model];
      check.check(`${out}: TEXCOORD_${ext.texCoord} present`, `TEXCOORD_${ext.texCoord}` in p.attributes);
      const cluster = ktx(ext.cluster);
      check.check(`${out}: cluster texture RGBA16F ${ext.width}x${ext.height}`, cluster.vkFormat === 97 && cluster.pixelWidth === ext.width &&
                  cluster.pixelHeight === ext.height && cluster.layerCount === 0);
      const data = new DataView(cluster.levels[0].levelData.buffer, cluster.levels[0].levelData.byteOffset);
      let ok = true, covered = 0;
      for (let t = 0; t < ext.width * ext.height; t++) {
        const k = half(data.getUint16(8 * t, true)), code = half(data.getUint16(8 * t + 2, true));
        ok &&= Number.isInteger(k) && k >= 0 && k < model.clusters && [0, 1, 2].includes(code) && (code > 0 || k === 0);
        if (code > 0) covered++;
      }
      check.check(`${out}: cluster texels are cluster indices and coverage codes`, ok && covered > 0, `${covered} covered`);
      const weights = ktx(ext.weights);
      check.check(`${out}: weights texture a 2D array of ceil(N / 4) layers`, weights.vkFormat === 97 && weights.pixelWidth === ext.width &&
                  weights.layerCount === Math.ceil(model.terms / 4));
    }
}

async function checkPair(out, source) {
  const bytes = readFileSync(out);
  const report = await validator.validateBytes(new Uint8Array(bytes), { uri: out, maxIssues: 200 });
  check.check(`${out}: 0 validator errors`, report.issues.numErrors === 0,
              report.issues.messages.filter((m) => m.severity === 0).slice(0, 5).map((m) => `${m.code} ${m.pointer || ''} ${m.message}`).join('; '));
  const known = (m) => /^\/images\/\d+(\/mimeType)?$/.test(m.pointer || '') && ['VALUE_NOT_IN_LIST', 'IMAGE_UNRECOGNIZED_FORMAT'].includes(m.code);
  check.check(`${out}: warnings only about KTX2 images`, report.issues.messages.filter((m) => m.severity === 1).every(known));
  console.log(`${out}: ${report.issues.numErrors} errors, ${report.issues.numWarnings} warnings, ${report.issues.numInfos} infos`);

  const [a, b] = [await load(out), await load(source)];
  const [s, t] = [await summary(a), await summary(b)];
  for (const key of ['nodes', 'materials', 'textures'])
    check.check(`${out}: ${key} as in the source`, s[key] === t[key], `${s[key]} vs ${t[key]}`);
  check.check(`${out}: as many meshes drawn as in the source`, s.meshes.length === t.meshes.length, `${s.meshes.length} vs ${t.meshes.length}`);
  const models = a.parser.json.extensions.PRT_transfer.models;
  const texel = a.parser.json.meshes.some((m) => m.primitives.some((p) => 'cluster' in ((p.extensions || {}).PRT_transfer || {})));
  if (texel) checkTexels(out, bytes, models);
  const kinds = new Set();
  s.meshes.forEach((mesh, i) => {
    const other = t.meshes[i];
    if (!other) return;
    check.check(`${out}: mesh ${i} world matrix as in the source`,
                mesh.matrixWorld.elements.every((x, k) => Math.abs(x - other.matrixWorld.elements[k]) <= 1e-6 * (1 + Math.abs(x))));
    check.check(`${out}: mesh ${i} vertex count as in the source`,
                mesh.geometry.attributes.position.count === other.geometry.attributes.position.count);
    const names = Object.keys(mesh.geometry.attributes);
    check.check(`${out}: mesh ${i} has at most 16 attributes`, names.length <= 16, names.join(' '));
    const albedo = mesh.geometry.attributes._prt_albedo;
    check.check(`${out}: mesh ${i} has _PRT_ALBEDO in [0, 1]`, !!albedo && Array.from(albedo.array).every((v) => v >= 0 && v <= 1));
    // The primitive's own extension (a mixed scene has a per-texel and a per-vertex model).
    const where = a.parser.associations.get(mesh);
    const ext = a.parser.json.meshes[where.meshes].primitives[where.primitives].extensions.PRT_transfer;
    const model = models[ext.model];
    check.check(`${out}: mesh ${i} names a model of the file`, !!model, `model ${ext.model} of ${models.length}`);
    if (!model) return;
    kinds.add('width' in ext ? 'texel' : 'vertex');
    if ('width' in ext) {
      check.check(`${out}: mesh ${i} (per texel) has no other _PRT_ attribute`, names.filter((n) => n.startsWith('_prt_')).length === 1, names.join(' '));
      return;
    }
    const cluster = mesh.geometry.attributes._prt_cluster;
    check.check(`${out}: mesh ${i} has _PRT_CLUSTER`, !!cluster);
    if (cluster)
      check.check(`${out}: mesh ${i} cluster indices are integers in [0, K)`,
                  Array.from(cluster.array).every((k) => Number.isInteger(k) && k >= 0 && k < model.clusters));
    const weights = names.filter((n) => n.startsWith('_prt_weights')).length;
    check.check(`${out}: mesh ${i} has ceil(N / 4) weight attributes`, weights === Math.ceil(model.terms / 4), `${weights}`);
  });
  // A mixed scene (two models): per-texel and per-vertex primitives, each model used by its kind.
  if (models.length > 1) check.check(`${out}: a mixed scene draws both kinds`, kinds.size === 2, [...kinds].join(' '));
}

for (const pair of argument('pairs').split(',').filter(Boolean)) {
  const [out, source] = pair.split('=');
  await checkPair(out, source);
}
check.finish();
