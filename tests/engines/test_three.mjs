// The three.js export (a probe volume) as three.js evaluates it: three's own SphericalHarmonics3
// (fromArray, getIrradianceAt) and the shader chunk's shGetIrradianceAt (ShaderChunk.lights_pars_begin,
// compiled to JS per channel) give E(n)/pi (after the Lambert 1/pi) equal to prt's, for every valid
// probe on axis and random directions under both HDRIs; probes/threejs/prt_probe_volume.js's sample()
// returns each valid probe's own SH at its position. (The blending and the per-object shader hook are
// tested in headless Chromium by probes/threejs/test/browser_test.mjs.)
// Usage: node test_three.mjs --work DIR (the engines_fixture output)
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { ShaderChunk, SphericalHarmonics3, Vector3 } from 'three';
import { Checker, argument, fixtureFolders, glslFunction } from './common.mjs';

const { PrtProbeVolume } = await import('../../probes/threejs/prt_probe_volume.js');
const work = argument('work');
const check = new Checker('engines_three');
const shGetIrradianceAt = glslFunction(ShaderChunk.lights_pars_begin, 'shGetIrradianceAt', 'normal', ['shCoefficients']);

for (const { name, dir, truth } of fixtureFolders(work)) {
  const file = JSON.parse(readFileSync(join(dir, 'threejs.json'), 'utf8'));
  const volume = new PrtProbeVolume(file);
  check.check(`${name}: every probe listed`, volume.count === truth.probes.length);
  for (const probe of truth.probes) {
    check.check(`${name} probe ${probe.index}: valid flag`, (file.valid[probe.index] === 1) === probe.valid);
    if (!probe.valid) continue;
    const sh = new SphericalHarmonics3().fromArray(file.sh.slice(27 * probe.index, 27 * probe.index + 27));
    const scale = check.scaleOf(probe.e_over_pi);
    const coefficients = sh.coefficients.map((v) => [v.x, v.y, v.z]);
    truth.directions.forEach((n, k) => {
      const e = sh.getIrradianceAt(new Vector3(...n), new Vector3());
      check.close(`${name} probe ${probe.index} getIrradianceAt n=${n}`, [e.x / Math.PI, e.y / Math.PI, e.z / Math.PI], probe.e_over_pi[k], scale, 1e-4);
      const g = shGetIrradianceAt(n, { shCoefficients: coefficients });
      check.close(`${name} probe ${probe.index} shGetIrradianceAt n=${n}`, g.map((v) => v / Math.PI), probe.e_over_pi[k], scale, 1e-4);
    });
    const blended = volume.sample(new Vector3(...probe.position));
    const own = blended.coefficients.flatMap((v) => [v.x, v.y, v.z]);
    check.close(`${name} probe ${probe.index}: volume.sample at the probe`, own, file.sh.slice(27 * probe.index, 27 * probe.index + 27), check.scaleOf(own), 1e-6);
  }
}
check.finish();
