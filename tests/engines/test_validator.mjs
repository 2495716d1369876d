// Every glTF binary prt writes, checked by the Khronos glTF validator (npm gltf-validator): the
// EXT_lights_image_based exports (both HDRIs, the constant and the smooth environment; OBJ scenes go
// through prt's own GLB writer first; a GLB scene is re-written with its buffers merged), `prt bake --gltf` (transfer attributes) and `prt shade -o .glb`
// (COLOR_0 tone-mapped to [0, 1] plus the linear _PRT_RADIANCE) must have 0 errors. The shaded file's
// radiance must exceed 1 somewhere, so that the COLOR_0 rule was exercised.
// Usage: node test_validator.mjs --work DIR (the engines_fixture output)
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { createRequire } from 'node:module';
import { Checker, argument, fixtureFolders } from './common.mjs';

const require = createRequire(import.meta.url);
const validator = require('gltf-validator');
const work = argument('work');
const check = new Checker('engines_validator');

const files = fixtureFolders(work).map((f) => join(f.dir, 'gltf.glb'));
files.push(join(work, 'constant', 'gltf.glb'), join(work, 'smooth', 'gltf.glb'), join(work, 'other', 'transfer.glb'), join(work, 'other', 'shaded.glb'),
           join(work, 'other', 'rewritten.glb'));
for (const file of files) {
  const report = await validator.validateBytes(new Uint8Array(readFileSync(file)), { uri: file, maxIssues: 100 });
  const errors = report.issues.messages.filter((m) => m.severity === 0);
  check.check(`${file}: 0 validator errors`, report.issues.numErrors === 0,
              `${report.issues.numErrors} errors: ${errors.slice(0, 5).map((m) => `${m.code} ${m.pointer || ''} ${m.message}`).join('; ')}`);
  console.log(`${file}: ${report.issues.numErrors} errors, ${report.issues.numWarnings} warnings, ${report.issues.numInfos} infos`);
}

// The shaded GLB's attributes, read back from its own accessors.
const glb = readFileSync(join(work, 'other', 'shaded.glb'));
const jsonLength = glb.readUInt32LE(12);
const doc = JSON.parse(glb.toString('utf8', 20, 20 + jsonLength));
const bin = glb.subarray(20 + jsonLength + 8);
const floats = (accessor) => {
  const a = doc.accessors[accessor], v = doc.bufferViews[a.bufferView];
  return new Float32Array(bin.buffer.slice(bin.byteOffset + v.byteOffset, bin.byteOffset + v.byteOffset + v.byteLength));
};
const attributes = doc.meshes[0].primitives[0].attributes;
check.check('shaded.glb: has COLOR_0 and _PRT_RADIANCE', 'COLOR_0' in attributes && '_PRT_RADIANCE' in attributes, JSON.stringify(attributes));
if (!('_PRT_RADIANCE' in attributes) || !('COLOR_0' in attributes)) check.finish();
const colour = floats(attributes.COLOR_0), radiance = floats(attributes._PRT_RADIANCE);
check.check('shaded.glb: the radiance exceeds 1 somewhere', radiance.some((v) => v > 1), `max ${Math.max(...radiance)}`);
check.check('shaded.glb: COLOR_0 = L / (1 + L) of _PRT_RADIANCE, in [0, 1]',
            colour.every((c, i) => c >= 0 && c <= 1 && Math.abs(c - Math.max(radiance[i], 0) / (1 + Math.max(radiance[i], 0))) < 1e-6));
check.finish();
