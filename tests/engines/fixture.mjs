// ctest fixture of the engine tests: bakes a 3 x 2 x 3 probe grid of the test scene under each
// environment given, with the real `prt`, and writes every engine export and prt's answers through
// engine_fixture (one folder per environment), plus the GLB files the other commands write (prt bake
// --gltf, prt shade -o .glb) and a glTF export under a constant environment (3, 1.5, 0.75).
//
// Usage: node fixture.mjs --prt PRT --fixture ENGINE_FIXTURE --work DIR --env A.exr[,B.exr...]
import { mkdirSync, rmSync, writeFileSync } from 'node:fs';
import { basename, join } from 'node:path';
import { argument, run, writeScene } from './common.mjs';

const prt = argument('prt'), fixture = argument('fixture'), work = argument('work');
const environments = argument('env').split(',');
rmSync(work, { recursive: true, force: true });
mkdirSync(work, { recursive: true });
const scene = join(work, 'scene.obj');
writeScene(scene);

const names = [];
for (const env of environments) {
  const name = basename(env).replace(/\.\w+$/, '');
  const dir = join(work, name);
  mkdirSync(dir, { recursive: true });
  const probes = join(dir, 'probes.prtprobes');
  run(prt, ['probes', scene, '--env', env, '--grid', '3,2,3', '--bands', '3', '--rays', '512', '--surface-samples', '64', '--format', 'prt', '-o', probes, '-q']);
  run(fixture, [probes, scene, env, dir]);
  names.push(name);
}

// An analytic environment rendered by prt's own preview of it, and one probe baked under it.
function analyticFixture(name, spec, bands, width) {
  const dir = join(work, name);
  mkdirSync(dir, { recursive: true });
  const env = join(dir, `${name}.exr`), probes = join(dir, 'probes.prtprobes');
  run(prt, ['light', spec, '--bands', String(bands), '-o', join(dir, `${name}.json`), '--preview', env, '--preview-width', String(width)]);
  run(prt, ['probes', scene, '--env', env, '--points', writePoints(join(dir, 'points.json')), '--bands', '3', '--rays', '256', '--surface-samples', '16', '--format', 'prt', '-o', probes, '-q']);
  run(fixture, [probes, scene, env, dir]);
}
// The constant environment (exactly 3, 1.5, 0.75), and a smooth (3-band) one, where a 16-pixel
// specular cube resolves the lighting.
analyticFixture('constant', 'constant:3,1.5,0.75', 1, 64);
analyticFixture('smooth', 'directional:1,0.5,0.3:1,0.8,0.6+constant:0.6,0.6,0.6', 3, 256);

// The other GLB writers: transfer in glTF (prt bake --gltf) and shaded radiance (prt shade -o .glb),
// lit brightly enough that the radiance exceeds 1; and a glTF scene through the glTF export.
const other = join(work, 'other');
mkdirSync(other, { recursive: true });
run(prt, ['bake', scene, '-o', join(other, 'scene.prt'), '--transfer', 'unshadowed', '--gltf', join(other, 'transfer.glb')]);
run(prt, ['light', 'directional:0.3,1,0.2:4,3,2+constant:0.5,0.5,0.5', '--bands', '3', '-o', join(other, 'bright.json')]);
run(prt, ['shade', scene, join(other, 'scene.prt'), '--light', join(other, 'bright.json'), '-o', join(other, 'shaded.glb')]);
// A glTF scene re-written by the glTF export (its buffers merged into the new BIN chunk).
run(prt, ['probes', join(other, 'shaded.glb'), '--env', join(work, 'smooth', 'smooth.exr'), '--points', join(work, 'smooth', 'points.json'),
          '--rays', '64', '--surface-samples', '4', '--specular-size', '8', '--format', 'gltf', '-o', join(other, 'rewritten.glb'), '-q']);
writeFileSync(join(work, 'fixtures.json'), JSON.stringify(names));
console.log(`fixture: ${names.join(', ')}, constant, smooth, other in ${work}`);
console.log('fixture: 1 passed, 0 failed');

function writePoints(path) {
  writeFileSync(path, JSON.stringify([[1.5, 0.5, 1.5]]));
  return path;
}
