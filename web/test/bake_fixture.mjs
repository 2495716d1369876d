// The bakes the web/ tests relight, as `prt bake MESH --gltf OUT.glb` writes them (the engine glTF,
// docs/formats.md), and `prt light` JSON files of an environment: sky.json (--sun none), sun.json (the
// map's own sun as a disc) and disc.json (the map plus a 2-degree disc high in the sky, so that shadows
// fall on the object). All with --window none: the page and `prt render --window none` shade the same
// coefficients. `prt render OUT.glb OUT.glb` renders the same file.
import { existsSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { run } from '../../tests/engines/common.mjs';

/// Bakes per-vertex interreflected transfer (1 bounce, with the bounce-only part the sun needs) of
/// `mesh` into work/NAME.glb; returns the file name, or null when the mesh is missing (optional assets).
export function bakeGlb({ prt, mesh, work, name, bands = 3, samples = 256, extra = [] }) {
  if (!existsSync(mesh)) return null;
  run(prt, ['bake', mesh, '--transfer', 'interreflected', '--bounces', '1', '--samples', String(samples), '--bands', String(bands),
            ...extra, '-q', '-o', join(work, `${name}.prt`), '--gltf', join(work, `${name}.glb`)]);
  return `${name}.glb`;
}

/// Writes sky.json, sun.json and disc.json of `env` with `bands` bands into work.
export function writeLights({ prt, env, work, bands }) {
  const light = (name, extra) => run(prt, ['light', env, '--bands', String(bands), '--window', 'none', ...extra, '-o', join(work, name)]);
  light('sky.json', ['--sun', 'none']);
  light('sun.json', []);
  light('disc.json', ['--sun', '0.4,1,0.3,6,5.6,5,2']);
  if (!(JSON.parse(readFileSync(join(work, 'sun.json'), 'utf8')).discs || []).length) throw new Error(`${env}: prt light found no sun`);
}

/// The sphere-on-a-floor bake and the three lights: {glb}.
export function prepareBake({ prt, mesh, env, work, bands }) {
  const glb = bakeGlb({ prt, mesh, work, name: 'baked', bands });
  writeLights({ prt, env, work, bands });
  return { glb };
}
