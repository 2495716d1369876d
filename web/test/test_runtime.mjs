// Acceptance test of the three.js runtime (web/prt_transfer.js) in headless Chromium with the real
// three.js of web/package-lock.json: its pixels against `prt render`'s for the same bake, camera and
// lighting. Both sides render linear radiance (prt: EXR; the page: a float render target), and the
// comparison runs over the object's pixels (the page's coverage, less a 1-pixel rim where the two
// rasterisers may cover differently): rel_rms = sqrt(sum |a - b|^2 / sum |b|^2) <= 1%, and the 99th
// percentile of |a - b| / rms(b) is printed.
//
// Cases (each: the bake's glb, a `prt light` JSON, camera, rotation, sun): per-vertex diffuse
// interreflected with the sun off and on, and with the environment rotated.
//
// Usage: node web/test/test_runtime.mjs --prt <prt> --env <sky.exr> --mesh <mesh> [--work DIR]
//        [--break order|rotation]  (a deliberately wrong runtime: swapped SH coefficients or no rotation;
//                                   the test must then fail)
// Exit status 0 pass, 1 fail, 77 skipped (no Chromium).
import { mkdirSync, mkdtempSync, readFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import { FloatType } from 'three';
import { EXRLoader } from 'three/examples/jsm/loaders/EXRLoader.js';
import { argument, run } from '../../tests/engines/common.mjs';
import { launch, openPage, requireBrowser, serve } from './browser.mjs';
import { prepareBake } from './bake_fixture.mjs';

requireBrowser();
const prt = argument('prt');
const env = resolve(argument('env'));
const mesh = resolve(argument('mesh'));
const work = resolve(argument('work', mkdtempSync(join(tmpdir(), 'prt-web-runtime-'))));
const breakage = argument('break', '');
mkdirSync(work, { recursive: true });
const size = 256;
const bands = 3;

const bake = prepareBake({ prt, mesh, env, work, bands });

const cases = [
  { name: 'sun off', light: 'sky.json', camera: [30, 25], rotate: [0, 0, 0], sun: false },
  { name: 'sun on (a 2-degree disc high in the sky: PCSS shadow, bounce)', light: 'disc.json', camera: [30, 25], rotate: [0, 0, 0], sun: true },
  { name: 'sun on (the map\'s own sun, found by prt light)', light: 'sun.json', camera: [30, 25], rotate: [0, 0, 0], sun: true },
  { name: 'rotated environment, sun on', light: 'disc.json', camera: [-40, 30], rotate: [70, 20, 0], sun: true },
];

function readExr(path) {
  const data = new EXRLoader().setDataType(FloatType).parse(readFileSync(path).buffer.slice(0));
  const { width, height } = data;
  const channels = data.data.length / (width * height);
  const out = new Float32Array(3 * width * height);
  for (let y = 0; y < height; y++) for (let x = 0; x < width; x++) for (let c = 0; c < 3; c++) {
    out[3 * (y * width + x) + c] = data.data[((height - 1 - y) * width + x) * channels + c];  // EXRLoader rows run bottom first
  }
  return { width, height, pixels: out };
}

/// rel_rms and the 99th percentile of |a - b| / rms(b) over the covered pixels (alpha 1 in the page's
/// image, and in all 8 neighbours).
export function compareImages(page, reference, width, height) {
  const covered = (x, y) => x >= 0 && y >= 0 && x < width && y < height && page[4 * (y * width + x) + 3] > 0.5;
  const diffs = [];
  let sumSq = 0, refSq = 0;
  for (let y = 0; y < height; y++) for (let x = 0; x < width; x++) {
    let inside = true;
    for (let dy = -1; dy <= 1; dy++) for (let dx = -1; dx <= 1; dx++) inside = inside && covered(x + dx, y + dy);
    if (!inside) continue;
    for (let c = 0; c < 3; c++) {
      const a = page[4 * (y * width + x) + c], b = reference[3 * (y * width + x) + c];
      sumSq += (a - b) ** 2;
      refSq += b * b;
      diffs.push(Math.abs(a - b));
    }
  }
  const rms = Math.sqrt(refSq / Math.max(1, diffs.length));
  diffs.sort((p, q) => p - q);
  return { pixels: diffs.length / 3, relRms: Math.sqrt(sumSq / refSq), p99: diffs[Math.floor(0.99 * (diffs.length - 1))] / rms,
           max: diffs[diffs.length - 1] / rms };
}

const server = await serve(work);
const browser = await launch(size, size);
let failed = false;
try {
  const page = await openPage(browser.context, `http://127.0.0.1:${server.port}/web/test/harness.html${breakage ? `?break=${breakage}` : ''}`, 'prtHarnessReady');
  for (const c of cases) {
    const reference = join(work, `reference_${cases.indexOf(c)}.exr`);
    run(prt, ['render', bake.renderMesh, bake.renderTransfer, '--env', join(work, c.light), '--window', 'none',
              '--background', 'black', '--size', `${size}x${size}`, '--camera', `${c.camera[0]},${c.camera[1]},auto`,
              '--rotate', c.rotate.join(','), '--sun', c.sun ? 'auto' : 'none', '-o', reference]);
    await page.reload();
    await page.waitForFunction(() => window.prtHarnessReady === true);
    const info = await page.evaluate((a) => window.prtLoad(a), { glb: `/work/${bake.glb}`, light: `/work/${c.light}` });
    const shot = await page.evaluate((a) => window.prtRender(a), { width: size, height: size, camera: { azimuth: c.camera[0], elevation: c.camera[1] },
                                                                  rotate: c.rotate, sun: c.sun });
    const pixels = new Float32Array(Buffer.from(shot.pixels, 'base64').buffer.slice(0));
    const ref = readExr(reference);
    const r = compareImages(pixels, ref.pixels, size, size);
    if (process.env.PRT_DEBUG) { const i = (128 * size + 128); console.log('page', pixels.slice(4 * i, 4 * i + 4), 'prt', ref.pixels.slice(3 * i, 3 * i + 3)); }
    const ok = r.relRms <= 0.01 && r.pixels > 0.05 * size * size && info.maxAttributes <= 16 && page.errors.length === 0;
    console.log(`${ok ? 'ok  ' : 'FAIL'} ${c.name}: rel_rms ${(100 * r.relRms).toFixed(3)}% over ${r.pixels} pixels ` +
                `(bound 1%); 99th percentile |error| ${(100 * r.p99).toFixed(2)}% of rms, max ${(100 * r.max).toFixed(1)}%; ` +
                `${info.maxAttributes} vertex attributes (MAX_VERTEX_ATTRIBS ${info.gl}); three r${info.three}`);
    if (page.errors.length) console.log(`  page errors: ${page.errors.join('; ')}`);
    if (!ok) failed = true;
  }
} catch (e) {
  failed = true;
  console.error(`FAIL: ${e.stack || e.message}`);
} finally {
  await browser.close();
  server.close();
}
console.log(failed ? 'FAIL' : 'PASS');
process.exit(failed ? 1 : 0);
