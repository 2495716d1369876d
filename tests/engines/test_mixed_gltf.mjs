// The engine glTF of a mixed scene (`prt bake --lightmap N --texel-parts Floor,Wall --gltf`; docs/formats.md,
// "Mixed scenes" under the engine glTF) through test_engine_gltf.mjs (the Khronos validator, three.js's
// GLTFLoader, ktx-parse): the room of web/test/lightmap_scene.mjs (Floor and Wall per texel, Box per
// vertex) with the file's UVs and with generated ones (--uv generate: the file is written from
// ROOM.mesh.glb, its source). Then the check must fail on deliberately broken copies: the per-vertex
// primitive without _PRT_CLUSTER, a per-texel primitive without its lightmap UV set, a primitive naming
// a model the file does not have.
// Usage: node test_mixed_gltf.mjs --prt PRT --work DIR
import { spawnSync } from 'node:child_process';
import { copyFileSync, mkdirSync, rmSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { Checker, argument, editGlb, run } from './common.mjs';
import { writeMixedScene } from '../../web/test/lightmap_scene.mjs';

const here = dirname(fileURLToPath(import.meta.url));
const prt = argument('prt'), work = argument('work');
rmSync(work, { recursive: true, force: true });
mkdirSync(work, { recursive: true });
const check = new Checker('engines_mixed_gltf');
const scene = writeMixedScene(work);
const bake = (name, extra) => run(prt, ['bake', scene, '--lightmap', '32', '--texel-parts', 'Floor,Wall', '--transfer', 'interreflected',
                                         '--bands', '3', '--samples', '16', '--bounces', '1', '-q', ...extra, '-o', join(work, `${name}.prt`),
                                         '--gltf', join(work, `${name}.glb`)]);
bake('mixed', []);
bake('generated', ['--uv', 'generate']);

// Runs test_engine_gltf.mjs on OUT=SOURCE pairs; its exit status.
const engineTest = (pairs) => {
  const r = spawnSync(process.execPath, [join(here, 'test_engine_gltf.mjs'), '--pairs', pairs.join(',')], { encoding: 'utf8' });
  const lines = `${r.stdout}${r.stderr}`.trim().split('\n');
  return { status: r.status, failures: lines.filter((l) => l.startsWith('FAIL')), last: lines.pop() };
};
const good = engineTest([`${join(work, 'mixed.glb')}=${scene}`, `${join(work, 'generated.glb')}=${join(work, 'generated.mesh.glb')}`]);
console.log(`the two exports: exit ${good.status} (${good.last})`);
good.failures.forEach((l) => console.log(`  ${l}`));
check.check('test_engine_gltf passes on the mixed exports', good.status === 0, `exit ${good.status}`);

// A copy of mixed.glb edited by `edit(primitive, node name)` for every primitive.
const broken = [
  ['the Box (per vertex) without _PRT_CLUSTER', (p, name) => { if (name === 'Box') delete p.attributes._PRT_CLUSTER; }],
  ['the Floor (per texel) without its lightmap UV set', (p, name) => { if (name === 'Floor') p.extensions.PRT_transfer.texCoord = 3; }],
  ['the Box naming model 2 of 2', (p, name) => { if (name === 'Box') p.extensions.PRT_transfer.model = 2; }],
];
for (const [what, edit] of broken) {
  const copy = join(work, 'broken.glb');
  copyFileSync(join(work, 'mixed.glb'), copy);
  editGlb(copy, (j) => j.nodes.forEach((n) => j.meshes[n.mesh].primitives.forEach((p) => edit(p, n.name))));
  const r = engineTest([`${copy}=${scene}`]);
  console.log(`${what}: exit ${r.status} (${r.failures[0] || r.last})`);
  // Its own failing check, not a crash.
  check.check(`test_engine_gltf fails on ${what}`, r.status === 1 && r.failures.length > 0, `exit ${r.status}`);
}
check.finish();
