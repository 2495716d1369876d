// PrtTransferPlugin on damaged files, in node with three's GLTFLoader: a glb from `prt bake --gltf` loads
// (models, marked meshes, attribute count <= 16), and each damaged copy (its JSON edited) is refused with
// one line naming the extension and the problem, not a crash or a silently wrong model.
// Usage: node web/test/test_plugin.mjs --prt <prt> --mesh <mesh> [--work DIR]
import { mkdirSync, mkdtempSync, readFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import { argument } from '../../tests/engines/common.mjs';
import { bakeGlb } from './bake_fixture.mjs';

// GLTFLoader decodes images with createImageBitmap; node has none, and these files have no images.
globalThis.self = globalThis;
const { GLTFLoader } = await import('three/examples/jsm/loaders/GLTFLoader.js');
const { PrtTransferPlugin } = await import('../prt_transfer.js');

const prt = argument('prt');
const work = resolve(argument('work', mkdtempSync(join(tmpdir(), 'prt-web-plugin-'))));
mkdirSync(work, { recursive: true });
const glb = readFileSync(join(work, bakeGlb({ prt, mesh: resolve(argument('mesh')), work, name: 'plugin', samples: 16 })));

// The glb with its JSON changed by edit(json).
function edited(edit) {
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
  try { await load(edited(edit)); } catch (e) { message = String(e.message); }
  check(expected.test(message) && !message.includes('\n'), `${what}: refused with "${message}"`);
}
console.log(failed ? 'FAIL' : 'PASS');
process.exit(failed ? 1 : 0);
