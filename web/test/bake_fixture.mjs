// The bake the web/ tests relight: per-vertex interreflected transfer (1 bounce, with the bounce-only part
// the sun needs) of a mesh as a PRT_transfer .glb, and three `prt light` JSON files of an environment:
// sky.json (--sun none), sun.json (the map's own sun as a disc) and disc.json (the map plus a 2-degree
// disc high in the sky, so that shadows fall on the object). All with --window none: the page and
// `prt render --window none` shade the same coefficients.
import { readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { run } from '../../tests/engines/common.mjs';
import { draftGlb } from './draft_glb.mjs';

/// Returns {glb (file name in work), renderMesh, renderTransfer (what `prt render` takes)}.
export function prepareBake({ prt, mesh, env, work, bands }) {
  run(prt, ['bake', mesh, '--transfer', 'interreflected', '--bounces', '1', '--samples', '256', '--bands', String(bands),
            '--compress', '16,4', '-o', join(work, 'baked.cprt'), '--gltf', join(work, 'mesh.glb')]);
  writeFileSync(join(work, 'baked.glb'), draftGlb(readFileSync(join(work, 'mesh.glb')), readFileSync(join(work, 'baked.cprt')), [0.8, 0.8, 0.8]));
  const light = (name, extra) => run(prt, ['light', env, '--bands', String(bands), '--window', 'none', ...extra, '-o', join(work, name)]);
  light('sky.json', ['--sun', 'none']);
  light('sun.json', []);
  light('disc.json', ['--sun', '0.4,1,0.3,6,5.6,5,2']);
  if (!(JSON.parse(readFileSync(join(work, 'sun.json'), 'utf8')).discs || []).length) throw new Error(`${env}: prt light found no sun`);
  return { glb: 'baked.glb', renderMesh: mesh, renderTransfer: join(work, 'baked.cprt') };
}
