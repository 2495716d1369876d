// The Filament export (cmgen's sh.txt) as Filament's own code reads it: the npm `filament` wasm build
// (no WebGL needed) runs IndirectLight.getColorEstimate and getDirectionEstimate, the static helpers
// of filament/src/details/IndirectLight.cpp, on the 9 coefficients of every valid probe and of the sky.
//  - getColorEstimate(sh, -n) evaluates the shader's SH polynomial at n ("the exact same code used in
//    the shader for SH reconstruction"), times pi, clamped at 0: rgb * a / pi must be prt's E(n)/pi
//    (clamped at 0), on axis and random directions, for both HDRIs' grids;
//  - getDirectionEstimate(sh) is the direction the light travels, -normalize(luminance-weighted band 1):
//    it must be opposite to where prt's irradiance grows fastest, (E(+X) - E(-X), E(+Y) - E(-Y),
//    E(+Z) - E(-Z)) weighted by luminance, which holds only if the coefficients are in Filament's world
//    frame unmirrored (what probes/filament/README.md says).
// Usage: node test_filament.mjs --work DIR (the engines_fixture output)
import { createRequire } from 'node:module';
import { existsSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { Checker, argument, fixtureFolders } from './common.mjs';

const require = createRequire(import.meta.url);
const factory = require('filament');
const module = factory();
const Filament = (await Promise.resolve(module.ready || module)) || module;
const work = argument('work');
const check = new Checker('engines_filament');

function readShTxt(path) {
  const lines = readFileSync(path, 'utf8').trim().split('\n');
  check.check(`${path}: 9 lines`, lines.length === 9);
  const values = [];
  for (const line of lines) {
    const m = line.match(/^\(\s*([-\d.eE+]+),\s*([-\d.eE+]+),\s*([-\d.eE+]+)\); \/\/ L\d-?\d, irradiance, pre-scaled base$/);
    check.check(`${path}: cmgen line format`, m !== null, line);
    if (m) values.push(Number(m[1]), Number(m[2]), Number(m[3]));
  }
  return new Float32Array(values);
}

const luminance = [0.2126, 0.7152, 0.0722];
function checkProbe(what, sh, truth, directions) {
  const scale = check.scaleOf(truth);
  directions.forEach((n, k) => {
    const c = Filament.IndirectLight.getColorEstimate(sh, [-n[0], -n[1], -n[2]]);
    const got = [0, 1, 2].map((i) => (c[3] > 0 ? (c[i] * c[3]) / Math.PI : 0));
    check.close(`${what} n=${n}`, got, truth[k].map((v) => Math.max(v, 0)), scale, 1e-4);
  });
  const gradient = [0, 1, 2].map((a) => [0, 1, 2].reduce((s, c) => s + luminance[c] * (truth[2 * a][c] - truth[2 * a + 1][c]), 0));
  const length = Math.hypot(...gradient);
  const d = Filament.IndirectLight.getDirectionEstimate(sh);
  check.close(`${what} getDirectionEstimate`, d, gradient.map((g) => -g / length), 1, 1e-4);
}

for (const { name, dir, truth } of fixtureFolders(work)) {
  checkProbe(`${name} sky`, readShTxt(join(dir, 'filament_sky.txt')), truth.sky, truth.directions);
  for (const probe of truth.probes) {
    const file = join(dir, `filament_${probe.index}.txt`);
    check.check(`${name}: filament_${probe.index}.txt exists exactly for valid probes`, existsSync(file) === probe.valid);
    if (probe.valid) checkProbe(`${name} probe ${probe.index}`, readShTxt(file), probe.e_over_pi, truth.directions);
  }
}
check.finish();
