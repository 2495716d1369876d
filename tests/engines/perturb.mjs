// Each engine test must fail on a deliberately perturbed copy of the file it checks (a flipped sign,
// swapped faces, a renamed field, a broken script): this copies the fixture folder once per case,
// damages one file, runs the test on the copy and expects exit status 1. Prints one line per case.
// Usage: node perturb.mjs --work DIR (the engines_fixture output)
import { spawnSync } from 'node:child_process';
import { cpSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { Checker, argument, editGlb, fixtureFolders } from './common.mjs';

const here = dirname(fileURLToPath(import.meta.url));
const work = argument('work');
const first = fixtureFolders(work)[0].name;
const check = new Checker('engines_perturbed');

const editJson = (path, edit) => { const j = JSON.parse(readFileSync(path, 'utf8')); edit(j); writeFileSync(path, JSON.stringify(j)); };

const cases = [
  ['babylon', 'x term of irradianceCoefficients negated (lighting mirrored back)', (d) =>
    editGlb(join(d, first, 'gltf.glb'), (j) => { for (const k of [3, 4, 7]) j.extensions.EXT_lights_image_based.lights[0].irradianceCoefficients[k] = j.extensions.EXT_lights_image_based.lights[0].irradianceCoefficients[k].map((v) => -v); })],
  ['babylon', 'specular faces +X and -X swapped', (d) =>
    editGlb(join(d, 'smooth', 'gltf.glb'), (j) => { const f = j.extensions.EXT_lights_image_based.lights[0].specularImages[0]; [f[0], f[1]] = [f[1], f[0]]; })],
  ['filament', 'sign of L1-1 flipped in one sh.txt', (d) => {
    const p = join(d, first, 'filament_0.txt'), lines = readFileSync(p, 'utf8').split('\n');
    lines[1] = lines[1].replace(/\(\s*(-?)/, (m, s) => '(' + (s ? '' : '-'));
    writeFileSync(p, lines.join('\n'));
  }],
  ['three', 'sign of one y coefficient flipped', (d) => editJson(join(d, first, 'threejs.json'), (j) => { j.sh[3] = -j.sh[3]; })],
  ['bevy', 'the +X and -X cubes of the texture swapped (vkFormat kept)', (d) => {
    const p = join(d, first, 'bevy.ktx2'), b = readFileSync(p);
    // Level data is the last (NX * 2NY * 3NZ * 8) bytes; swap the first texel rows of the two halves.
    const size = 3 * 4 * 9 * 8, start = b.length - size, row = 3 * 8, half = 2 * row;  // y = NY: the negative half
    const a = Buffer.from(b.subarray(start, start + row)), c = Buffer.from(b.subarray(start + half, start + half + row));
    a.copy(b, start + half); c.copy(b, start);
    writeFileSync(p, b);
  }],
  ['validator', 'COLOR_0 pointed at the unclamped radiance accessor', (d) =>
    editGlb(join(d, 'other', 'shaded.glb'), (j) => { const a = j.meshes[0].primitives[0].attributes; a.COLOR_0 = a._PRT_RADIANCE; })],
  ['unity', 'sign of one x coefficient flipped', (d) => editJson(join(d, first, 'unity.json'), (j) => { const p = j.probes.find((q) => q.valid); p.sh[3] = -p.sh[3]; })],
  ['godot', 'format key renamed in the export', (d) => editJson(join(d, first, 'godot.json'), (j) => { j.kind = j.format; delete j.format; })],
];

for (const [test, what, perturb] of cases) {
  const copy = `${work}_perturbed`;
  rmSync(copy, { recursive: true, force: true });
  cpSync(work, copy, { recursive: true });
  perturb(copy);
  const r = spawnSync(process.execPath, [join(here, `test_${test}.mjs`), '--work', copy], { encoding: 'utf8' });
  const last = (r.stdout.trim().split('\n').pop() || '').trim();
  console.log(`${test}, ${what}: exit ${r.status} (${last})`);
  check.check(`test_${test} fails when ${what}`, r.status === 1 || (test === 'unity' && r.status === 77), `exit ${r.status}`);
  rmSync(copy, { recursive: true, force: true });
}
check.finish();
