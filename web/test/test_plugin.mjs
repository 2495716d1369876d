// PrtTransferPlugin on damaged files, in node with three's GLTFLoader: a glb from `prt bake --gltf` loads
// (models, marked meshes, attribute count <= 16), and each damaged copy (its JSON edited) is refused with
// one line naming the extension and the problem, not a crash or a silently wrong model. The same for a
// per-texel bake (`--lightmap 16x16`: the cluster and weights KTX2 images).
// Usage: node web/test/test_plugin.mjs --prt <prt> --mesh <mesh> [--work DIR]
import { mkdirSync, mkdtempSync, readFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import { argument } from '../../tests/engines/common.mjs';
import { bakeGlb } from './bake_fixture.mjs';
import { writeLightmapScene } from './lightmap_scene.mjs';

// GLTFLoader decodes images with createImageBitmap; node has none, and these files have no images.
globalThis.self = globalThis;
const { GLTFLoader } = await import('three/examples/jsm/loaders/GLTFLoader.js');
const { PrtTransferPlugin } = await import('../prt_transfer.js');

const prt = argument('prt');
const work = resolve(argument('work', mkdtempSync(join(tmpdir(), 'prt-web-plugin-'))));
mkdirSync(work, { recursive: true });
const glb = readFileSync(join(work, bakeGlb({ prt, mesh: resolve(argument('mesh')), work, name: 'plugin', samples: 16 })));
const texelGlb = readFileSync(join(work, bakeGlb({ prt, mesh: writeLightmapScene(work), work, name: 'plugin_texel', samples: 16, extra: ['--lightmap', '16x16'] })));

// The glb with its JSON changed by edit(json).
function edited(edit, glb) {
  const jsonLength = glb.readUInt32LE(12);
  const json = JSON.parse(glb.toString('utf8', 20, 20 + jsonLength));
  edit(json);
  let text = Buffer.from(JSON.stringify(json));
  text = Buffer.concat([text, Buffer.alloc((4 - (text.length % 4)) % 4, 0x20)]);
  const rest = glb.subarray(20 + jsonLength);
  const header = Buffer.alloc(20);
  header.write('glTF', 0);
  header.writeUInt32LE(2, 4);
  header.writeUInt32LE(20 + text.length + rest.length, 8);
  header.writeUInt32LE(text.length, 12);
  header.write('JSON', 16);
  return Buffer.concat([header, text, rest]);
}

const load = (bytes) => new GLTFLoader().register((p) => new PrtTransferPlugin(p))
  .parseAsync(bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.length), '');

let failed = false;
const check = (ok, text) => { console.log(`${ok ? 'ok  ' : 'FAIL'} ${text}`); if (!ok) failed = true; };

const good = await load(glb);
const meshes = [];
good.scene.traverse((o) => { if (o.isMesh && o.userData.prtTransfer) meshes.push(o); });
const model = good.userData.prtTransfer.models[0];
check(meshes.length === 1 && model.means.length === model.clusters * model.pointSize && model.bounce === true,
      `the bake loads: ${meshes.length} mesh with transfer, model ${model.kind} ${model.bands} bands ${model.clusters}x${model.terms}, bounce ${model.bounce}`);
check(Object.keys(meshes[0].geometry.attributes).length <= 16, `${Object.keys(meshes[0].geometry.attributes).length} vertex attributes (<= 16)`);

const damaged = [
  ['version 2', (j) => { j.extensions.PRT_transfer.version = 2; }, /PRT_transfer: version 2 is not 1/],
  ['a model with 0 clusters', (j) => { j.extensions.PRT_transfer.models[0].clusters = 0; }, /PRT_transfer model 0: .*clusters 0/],
  ['means shorter than K D\'', (j) => { j.extensions.PRT_transfer.models[0].clusters += 1; }, /PRT_transfer model 0: means hold \d+ values/],
  ['a primitive naming model 3', (j) => { j.meshes[0].primitives[0].extensions.PRT_transfer.model = 3; }, /PRT_transfer: mesh 0 names model 3 of 1/],
  ['bands 40', (j) => { j.extensions.PRT_transfer.models[0].bands = 40; }, /PRT_transfer model 0: .*bands 40/],
];
for (const [what, edit, expected] of damaged) {
  let message = 'loaded';
  try { await load(edited(edit, glb)); } catch (e) { message = String(e.message); }
  check(expected.test(message) && !message.includes('\n'), `${what}: refused with "${message}"`);
}

const texel = await load(texelGlb);
const lightmaps = [];
texel.scene.traverse((o) => { if (o.isMesh && o.userData.prtLightmap) lightmaps.push(o.userData.prtLightmap); });
const lm = lightmaps[0] || {};
const texelModel = texel.userData.prtTransfer.models[0];
check(lightmaps.length === 1 && lm.width === 16 && lm.height === 16 && lm.cluster.image.depth === 1 && lm.layers === Math.ceil(texelModel.terms / 4) &&
      (lm.layers === 0 || lm.weights.image.depth === lm.layers),
      `the per-texel bake loads: ${lightmaps.length} lightmap ${lm.width}x${lm.height}, ${lm.layers} weight layers, model ${texelModel.clusters}x${texelModel.terms}`);
const texelDamaged = [
  ['a per-texel primitive saying width 32', (j) => { j.meshes[0].primitives[0].extensions.PRT_transfer.width = 32; }, /PRT_transfer of mesh 0: its cluster texture is 16x16x1, the extension says 32x16/],
  ['a cluster image that is not KTX2', (j) => { j.images[j.meshes[0].primitives[0].extensions.PRT_transfer.cluster].mimeType = 'image/png'; }, /PRT_transfer of mesh 0: image \d+ is not an embedded KTX2 image/],
];
for (const [what, edit, expected] of texelDamaged) {
  let message = 'loaded';
  try { await load(edited(edit, texelGlb)); } catch (e) { message = String(e.message); }
  check(expected.test(message) && !message.includes('\n'), `${what}: refused with "${message}"`);
}
console.log(failed ? 'FAIL' : 'PASS');
process.exit(failed ? 1 : 0);
