// Browser test of the three.js probe volume and the page's display transform: bakes a 3x2x3 probe grid with the real `prt`, opens the
// example page (../index.html: real three.js from node_modules and ../prt_probe_volume.js) in headless
// Chromium driven by playwright-core, moves the sphere through the volume and, at each stop,
// screenshots the canvas and compares it with prt's own CPU render of the same sphere lit by the SH the
// blend must give there (tests/probes/probe_sphere_reference.cpp, shown through prt's own
// image::to_display with the page's exposure and tone map): exactly one probe at a probe's
// position and outside the grid (clamped), the mean of two probes at an edge midpoint, and the mean of
// the seven VALID corners at the centre of a cell one of whose corners lies inside the box (invalid).
//
// Usage: node test/browser_test.mjs --prt <prt binary> --reference <probe_sphere_reference binary>
//                                   --env <environment map> [--work <folder>]
// Exit status: 0 pass, 1 fail, 77 skipped (only when /usr/bin/chromium is missing; the reason is printed).
//
// TOLERANCE. Both sides compute albedo * E(n)/pi for the same 9 coefficients and encode sRGB to 8 bits.
// They differ by (a) the page's float32 shader arithmetic and three.js's 0.41666 exponent for 1/2.4
// (< 1e-4 relative), (b) the sphere mesh: 256 x 128 segments with interpolated, renormalised normals,
// whose direction differs from the true sphere's at the same pixel by at most ~(pi/128)^2/8 = 8e-5 rad,
// and (c) rounding to 8 bits on each side (0.5 LSB each). So every compared pixel (inside 0.97 of the
// radius, away from the rasterised silhouette) must be within 2/255 per channel, and the mean absolute
// difference below 0.5/255; a sign, scale, channel-order or handedness mistake moves values by tens of
// levels over large areas.
import { existsSync, mkdirSync, mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { createServer } from 'node:http';
import { tmpdir } from 'node:os';
import { dirname, extname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { argument, decodePng, run, writeScene } from '../../../tests/engines/common.mjs';

const here = dirname(fileURLToPath(import.meta.url));
const pageRoot = resolve(here, '..');
const chromiumPath = '/usr/bin/chromium';
const size = 256;
const albedo = 0.2;  // keeps albedo * E/pi below 1 everywhere for this scene and sky (nothing clips)

if (!existsSync(chromiumPath)) {
  console.log(`SKIP: ${chromiumPath} is not installed (Debian package 'chromium'); the three.js browser test needs it`);
  process.exit(77);
}
if (!existsSync(join(pageRoot, 'node_modules', 'three')) || !existsSync(join(pageRoot, 'node_modules', 'playwright-core'))) {
  console.error(`browser_test: ${pageRoot}/node_modules is missing: run 'npm ci' in ${pageRoot}`);
  process.exit(1);
}
const { chromium } = await import(join(pageRoot, 'node_modules', 'playwright-core', 'index.mjs'));

const prt = argument('prt');
const referenceTool = argument('reference');
const environment = argument('env');
const work = resolve(argument('work', mkdtempSync(join(tmpdir(), 'prt-browser-'))));
mkdirSync(work, { recursive: true });

const scenePath = join(work, 'scene.obj');
writeScene(scenePath);
// Grid 3 x 2 x 3 over the scene's bounds: probe (i, j, k) has index i + 3 (j + 2 k); probe 10,
// (0, 0.75, 0), lies inside the box (invalid).
const common = [scenePath, '--env', environment, '--grid', '3,2,3', '--bands', '3', '--rays', '1024', '-q'];
run(prt, ['probes', ...common, '--format', 'threejs', '-o', join(work, 'probes.json')]);
run(prt, ['probes', ...common, '--format', 'prt', '-o', join(work, 'probes.prtprobes')]);
const exported = JSON.parse(readFileSync(join(work, 'probes.json'), 'utf8'));
const position = (i) => exported.positions.slice(3 * i, 3 * i + 3);
const mean = (list) => [0, 1, 2].map((a) => list.reduce((s, i) => s + position(i)[a], 0) / list.length);
const cell = [7, 8, 10, 11, 13, 14, 16, 17];  // corners of the cell i in {1, 2}, j in {0, 1}, k in {1, 2}
const validCorners = cell.filter((i) => exported.valid[i] === 1);
if (exported.valid[10] !== 0 || validCorners.length !== 7) {
  console.error(`browser_test: expected probe 10 alone invalid in the cell, valid = ${exported.valid}`);
  process.exit(1);
}
// display: [exposure stops, tone map] of the page (prt_tone_map.js) and of the reference
// (image::to_display); [0, 'clamp'] is three's plain sRGB output. The last two stops show the sky at
// 4x (clipping in 'clamp' is what ACES avoids) and ACES at -1 stop.
const stops = [
  { at: position(17), probes: '17', what: 'at probe 17', display: [0, 'clamp'] },
  { at: mean([15, 16]), probes: '15+16', what: 'moved midway between probes 15 and 16', display: [0, 'clamp'] },
  { at: mean(cell), probes: validCorners.join('+'), what: 'centre of a cell with invalid corner 10', display: [0, 'clamp'] },
  { at: [3, 2, 3], probes: '17', what: 'outside the grid (clamped to probe 17)', display: [0, 'clamp'] },
  { at: position(17), probes: '17', what: 'at probe 17, exposure +2, ACES', display: [2, 'aces'] },
  { at: position(17), probes: '17', what: 'at probe 17, exposure -1, ACES', display: [-1, 'aces'] },
];

// Static server on the loopback interface: the page folder, and the bake under /work/.
const types = { '.html': 'text/html', '.js': 'text/javascript', '.mjs': 'text/javascript', '.json': 'application/json' };
const server = createServer((request, response) => {
  const url = new URL(request.url, 'http://127.0.0.1');
  const path = url.pathname.startsWith('/work/') ? join(work, url.pathname.slice(6)) : join(pageRoot, url.pathname);
  if (!path.startsWith(pageRoot) && !path.startsWith(work)) return response.writeHead(403).end();
  if (!existsSync(path)) return response.writeHead(404).end();
  response.writeHead(200, { 'Content-Type': types[extname(path)] || 'application/octet-stream' });
  response.end(readFileSync(path));
});
await new Promise((ok) => server.listen(0, '127.0.0.1', ok));
const port = server.address().port;

const profile = mkdtempSync(join(tmpdir(), 'prt-chromium-profile-'));
const context = await chromium.launchPersistentContext(profile, {
  executablePath: chromiumPath,
  headless: true,
  viewport: { width: size, height: size },
  deviceScaleFactor: 1,
  args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking',
         '--disable-component-update', '--disable-sync', '--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
});
let failed = false;
try {
  const page = await context.newPage();
  const errors = [];
  page.on('pageerror', (e) => errors.push(String(e)));
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  await page.goto(`http://127.0.0.1:${port}/index.html?file=/work/probes.json&albedo=${albedo}&size=${size}`);
  await page.waitForFunction(() => window.prtReady === true || window.prtError, null, { timeout: 60000 }).catch(() => {});
  const ready = await page.evaluate(() => window.prtReady === true);
  if (!ready) throw new Error(`the page did not render: ${errors.join('; ') || 'timeout'}`);
  for (const stop of stops) {
    await page.evaluate((d) => window.prtSetDisplay(d[0], d[1]), stop.display);
    const info = await page.evaluate((p) => window.prtRenderAt(p[0], p[1], p[2]), stop.at);
    const referenceFile = join(work, `reference_${stop.probes}_${stop.display.join('')}.rgba`);
    const referenceReport = run(referenceTool, [join(work, 'probes.prtprobes'), stop.probes, String(albedo), String(size), referenceFile,
                                                String(stop.display[0]), stop.display[1]]);
    const reference = readFileSync(referenceFile);
    const shot = decodePng(await page.locator('canvas').screenshot());
    if (shot.width !== size || shot.height !== size) throw new Error(`screenshot is ${shot.width}x${shot.height}, expected ${size}x${size}`);
    let compared = 0, sum = 0, worst = 0, worstAt = '';
    for (let i = 0; i < size * size; i++) {
      if (reference[4 * i + 3] !== 255) continue;
      compared++;
      for (let k = 0; k < 3; k++) {
        const d = Math.abs(shot.pixels[4 * i + k] - reference[4 * i + k]);
        sum += d;
        if (d > worst) { worst = d; worstAt = `pixel (${i % size}, ${Math.floor(i / size)}) channel ${k}: page ${shot.pixels[4 * i + k]}, prt ${reference[4 * i + k]}`; }
      }
    }
    const mean = sum / (3 * compared);
    console.log(`three.js r${info.three}, ${stop.what}: weights ${JSON.stringify(info.weights.map(([i, w]) => [i, +w.toFixed(4)]))}; reference: ${referenceReport.trim()}`);
    console.log(`  compared ${compared} pixels: mean |difference| ${mean.toFixed(4)} levels, max ${worst} levels${worst ? ' at ' + worstAt : ''}`);
    if (compared < 0.5 * size * size || worst > 2 || mean > 0.5) {
      failed = true;
      console.log(`FAIL: ${stop.what}: the page does not show the lighting prt computed (tolerance: max 2 levels, mean 0.5)`);
    }
  }
  if (!failed) console.log('PASS');
} catch (e) {
  failed = true;
  console.error(`FAIL: ${e.message}`);
} finally {
  await context.close();
  server.close();
  rmSync(profile, { recursive: true, force: true });
}
process.exit(failed ? 1 : 0);
