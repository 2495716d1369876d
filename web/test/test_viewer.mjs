// The web viewer (web/viewer.html) in headless Chromium: it loads a bake and a lighting file given as URL
// parameters, relights and shows the object with prt's camera, exposure and tone map, and its canvas
// equals `prt render`'s PNG of the same bake (rel_rms <= 1% of the sRGB-decoded display values over the
// object's pixels, less a 1-pixel rim; the 99th-percentile error is printed), with no console errors.
// Then: a mouse drag orbits (the canvas changes, the azimuth moves), the sun checkbox turns the discs off
// (the canvas then equals prt render of the same lighting without its discs), and with &probes= a sphere
// lit by prt's probe volume (probes/threejs) shares the scene; a mixed scene's engine glTF (per-texel and
// per-vertex primitives) shows prt render's image of its .prt pair.
// Usage: node web/test/test_viewer.mjs --prt <prt> --env <sky.exr> --mesh <mesh> [--work DIR] [--shot OUT.png]
// Exit status 0 pass, 1 fail, 77 skipped (no Chromium).
import { mkdirSync, mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import { argument, decodePng, run } from '../../tests/engines/common.mjs';
import { openPage, requireBrowser, runInBrowser } from './browser.mjs';
import { bakeGlb, prepareBake } from './bake_fixture.mjs';
import { writeMixedScene } from './lightmap_scene.mjs';

requireBrowser();
const prt = argument('prt');
const env = resolve(argument('env'));
const mesh = resolve(argument('mesh'));
const work = resolve(argument('work', mkdtempSync(join(tmpdir(), 'prt-web-viewer-'))));
const shotPath = argument('shot', '');
mkdirSync(work, { recursive: true });
const size = 256, camera = '30,25,auto', exposure = -2;
const bake = prepareBake({ prt, mesh, env, work, bands: 3 });
const mixedScene = writeMixedScene(work);
bakeGlb({ prt, mesh: mixedScene, work, name: 'mixed', samples: 64, extra: ['--lightmap', '64x64', '--texel-parts', 'Floor,Wall'] });
const noDiscs = JSON.parse(readFileSync(join(work, 'disc.json'), 'utf8'));
delete noDiscs.discs;
writeFileSync(join(work, 'disc_off.json'), JSON.stringify(noDiscs));

const srgbToLinear = (v) => { const s = v / 255; return s <= 0.04045 ? s / 12.92 : ((s + 0.055) / 1.055) ** 2.4; };

/// rel_rms of the sRGB-decoded values over the pixels that are not black in prt's image nor in any of
/// their 8 neighbours; the 99th percentile of |error| / rms.
function compareDisplay(shot, reference) {
  const lit = (x, y) => x >= 0 && y >= 0 && x < size && y < size && reference[4 * (y * size + x)] + reference[4 * (y * size + x) + 1] + reference[4 * (y * size + x) + 2] > 0;
  let sumSq = 0, refSq = 0;
  const diffs = [];
  for (let y = 0; y < size; y++) for (let x = 0; x < size; x++) {
    let inside = true;
    for (let dy = -1; dy <= 1; dy++) for (let dx = -1; dx <= 1; dx++) inside = inside && lit(x + dx, y + dy);
    if (!inside) continue;
    for (let c = 0; c < 3; c++) {
      const a = srgbToLinear(shot[4 * (y * size + x) + c]), b = srgbToLinear(reference[4 * (y * size + x) + c]);
      sumSq += (a - b) ** 2;
      refSq += b * b;
      diffs.push(Math.abs(a - b));
    }
  }
  diffs.sort((p, q) => p - q);
  const rms = Math.sqrt(refSq / Math.max(1, diffs.length));
  return { pixels: diffs.length / 3, relRms: Math.sqrt(sumSq / refSq), p99: diffs[Math.floor(0.99 * (diffs.length - 1))] / rms };
}

function prtRender(light, out, inputs = [join(work, bake.glb), join(work, bake.glb)]) {
  run(prt, ['render', ...inputs, '--env', join(work, light), '--window', 'none', '--background', 'black',
            '--size', `${size}x${size}`, '--camera', camera, '--exposure', String(exposure), '--tone-map', 'aces', '-o', join(work, out)]);
  return decodePng(readFileSync(join(work, out))).pixels;
}

let failed = false;
const check = (ok, text) => { console.log(`${ok ? 'ok  ' : 'FAIL'} ${text}`); if (!ok) failed = true; };
await runInBrowser(work, size, size, async ({ port, context }) => {
  const url = `http://127.0.0.1:${port}/web/viewer.html?glb=/work/${bake.glb}&env=/work/disc.json&camera=${camera}` +
              `&size=${size}x${size}&background=black&exposure=${exposure}&tonemap=aces`;
  const page = await openPage(context, url, 'prtViewerReady');
  const screenshot = async (from = page) => {
    // The canvas itself (preserveDrawingBuffer), without the control panel drawn over it.
    const data = await from.evaluate(() => { window.prtViewer.renderNow(); return document.querySelector('canvas').toDataURL('image/png'); });
    const png = Buffer.from(data.slice(data.indexOf(',') + 1), 'base64');
    return { png, pixels: decodePng(png).pixels };
  };
  const first = await screenshot();
  if (shotPath) writeFileSync(shotPath, first.png);
  let r = compareDisplay(first.pixels, prtRender('disc.json', 'reference.png'));
  check(r.relRms <= 0.01 && r.pixels > 0.05 * size * size,
        `viewer shows prt render's image: rel_rms ${(100 * r.relRms).toFixed(3)}% over ${r.pixels} pixels (bound 1%), 99th percentile ${(100 * r.p99).toFixed(2)}% of rms`);

  await page.evaluate(() => { const box = document.getElementById('sun'); box.click(); });
  const sunOff = await screenshot();
  r = compareDisplay(sunOff.pixels, prtRender('disc_off.json', 'reference_sun_off.png'));
  check(r.relRms <= 0.01, `sun checkbox off equals prt render without the discs: rel_rms ${(100 * r.relRms).toFixed(3)}%, 99th percentile ${(100 * r.p99).toFixed(2)}% of rms`);

  const box = await page.locator('canvas').boundingBox();
  await page.mouse.move(box.x + 200, box.y + 200);
  await page.mouse.down();
  await page.mouse.move(box.x + 150, box.y + 190, { steps: 5 });
  await page.mouse.up();
  const orbit = await page.evaluate(() => ({ ...window.prtViewer.orbit }));
  const dragged = await screenshot();
  let changed = 0;
  for (let i = 0; i < dragged.pixels.length; i++) changed += dragged.pixels[i] !== sunOff.pixels[i] ? 1 : 0;
  check(orbit.azimuth > 10 && changed > 1000, `drag orbits: azimuth 30 -> ${orbit.azimuth.toFixed(1)}, ${changed} values changed`);
  check(page.errors.length === 0, `no console errors (${page.errors.length}${page.errors.length ? ': ' + page.errors.join('; ') : ''})`);

  run(prt, ['probes', mesh, '--env', env, '--grid', '2,2,2', '--rays', '256', '--format', 'threejs', '-o', join(work, 'probes.json')]);
  const withProbes = await openPage(context, `${url}&probes=/work/probes.json`, 'prtViewerReady');
  const probe = await withProbes.evaluate(() => { window.prtViewer.renderNow(); const v = window.prtViewer; return { sh: v.volume.sample(v.probeSphere.position).coefficients[0].toArray(), meshes: v.relighting.meshes.length }; });
  check(probe.sh[0] > 0 && probe.meshes > 0 && withProbes.errors.length === 0,
        `probe volume and PRT material in one scene: the sphere's blended c0 ${probe.sh.map((v) => v.toFixed(3)).join(',')}, ${withProbes.errors.length} console errors`);
  // A mixed scene's engine glTF (Floor and Wall per texel, Box per vertex) against prt render of its .prt pair.
  const mixedPage = await openPage(context, url.replace(`glb=/work/${bake.glb}`, 'glb=/work/mixed.glb'), 'prtViewerReady');
  r = compareDisplay((await screenshot(mixedPage)).pixels, prtRender('disc.json', 'reference_mixed.png', [mixedScene, join(work, 'mixed.prt')]));
  check(r.relRms <= 0.01 && r.pixels > 0.05 * size * size && mixedPage.errors.length === 0,
        `mixed scene (per texel and per vertex in one glTF) shows prt render's image of its pair: rel_rms ${(100 * r.relRms).toFixed(3)}% over ${r.pixels} pixels, ` +
        `99th percentile ${(100 * r.p99).toFixed(2)}% of rms, ${mixedPage.errors.length} console errors`);
  return failed;
});
