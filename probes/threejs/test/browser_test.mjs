// Browser test of the three.js export: bakes a probe with the real `prt`, opens the example page
// (../index.html, real three.js from node_modules) in headless Chromium driven by playwright-core,
// screenshots the canvas and compares it with prt's own CPU render of the same sphere and probe
// (tests/probes/probe_sphere_reference.cpp).
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
import { spawnSync } from 'node:child_process';
import { existsSync, mkdirSync, mkdtempSync, readFileSync, writeFileSync, rmSync } from 'node:fs';
import { createServer } from 'node:http';
import { tmpdir } from 'node:os';
import { dirname, extname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { inflateSync } from 'node:zlib';

const here = dirname(fileURLToPath(import.meta.url));
const pageRoot = resolve(here, '..');
const chromiumPath = '/usr/bin/chromium';
const size = 256;
const albedo = 0.2;  // keeps albedo * E/pi below 1 everywhere for this scene and sky (nothing clips)

function argument(name, fallback) {
  const i = process.argv.indexOf(`--${name}`);
  if (i >= 0 && i + 1 < process.argv.length) return process.argv[i + 1];
  if (fallback !== undefined) return fallback;
  console.error(`browser_test: missing --${name}`);
  process.exit(1);
}

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

function run(command, args) {
  const r = spawnSync(command, args, { encoding: 'utf8' });
  if (r.status !== 0) {
    console.error(`browser_test: ${command} ${args.join(' ')} failed (${r.status}):\n${r.stdout}${r.stderr}`);
    process.exit(1);
  }
  return r.stdout;
}

// A floor with a box on it; one probe beside the box (it sees sky, floor and box).
function writeScene(path) {
  const v = [], f = [];
  const quad = (c, u, w, n) => {
    const base = v.length;
    for (let j = 0; j <= n; j++) for (let i = 0; i <= n; i++) v.push([0, 1, 2].map((k) => c[k] + (u[k] * i) / n + (w[k] * j) / n));
    for (let j = 0; j < n; j++)
      for (let i = 0; i < n; i++) {
        const a = base + j * (n + 1) + i, b = a + 1, cc = a + n + 1, d = cc + 1;
        f.push([a, b, d], [a, d, cc]);
      }
  };
  quad([-2, 0, -2], [0, 0, 4], [4, 0, 0], 16);
  quad([0.5, 0.001, -0.5], [0, 1, 0], [0, 0, 1], 4); // box +X face
  quad([-0.5, 1, -0.5], [0, 0, 1], [1, 0, 0], 4);     // box top
  quad([-0.5, 0.001, 0.5], [1, 0, 0], [0, 1, 0], 4);  // box +Z face
  const lines = v.map((p) => `v ${p.join(' ')}`).concat(f.map((t) => `f ${t[0] + 1} ${t[1] + 1} ${t[2] + 1}`));
  writeFileSync(path, lines.join('\n') + '\n');
}

// Minimal PNG decoder for Chromium's screenshots: 8-bit RGB or RGBA, not interlaced.
function decodePng(buffer) {
  let offset = 8, width = 0, height = 0, colorType = 0;
  const idat = [];
  while (offset < buffer.length) {
    const length = buffer.readUInt32BE(offset), type = buffer.toString('ascii', offset + 4, offset + 8);
    const data = buffer.subarray(offset + 8, offset + 8 + length);
    if (type === 'IHDR') {
      width = data.readUInt32BE(0);
      height = data.readUInt32BE(4);
      if (data[8] !== 8 || data[12] !== 0) throw new Error('unsupported PNG (bit depth or interlace)');
      colorType = data[9];
    } else if (type === 'IDAT') idat.push(data);
    offset += 12 + length;
  }
  const channels = colorType === 6 ? 4 : colorType === 2 ? 3 : 0;
  if (!channels) throw new Error(`unsupported PNG colour type ${colorType}`);
  const raw = inflateSync(Buffer.concat(idat)), stride = width * channels;
  const out = Buffer.alloc(width * height * 4);
  const prev = Buffer.alloc(stride), row = Buffer.alloc(stride);
  for (let y = 0; y < height; y++) {
    const filter = raw[y * (stride + 1)];
    for (let x = 0; x < stride; x++) {
      const value = raw[y * (stride + 1) + 1 + x];
      const a = x >= channels ? row[x - channels] : 0, b = prev[x], c = x >= channels ? prev[x - channels] : 0;
      let p;
      if (filter === 0) p = 0;
      else if (filter === 1) p = a;
      else if (filter === 2) p = b;
      else if (filter === 3) p = (a + b) >> 1;
      else {
        const pa = Math.abs(b - c), pb = Math.abs(a - c), pc = Math.abs(a + b - 2 * c);
        p = pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
      }
      row[x] = (value + p) & 255;
    }
    for (let x = 0; x < width; x++)
      for (let k = 0; k < 4; k++) out[4 * (y * width + x) + k] = k < channels ? row[x * channels + k] : 255;
    row.copy(prev);
  }
  return { width, height, pixels: out };
}

const scenePath = join(work, 'scene.obj');
writeScene(scenePath);
const common = [scenePath, '--env', environment, '--points', join(work, 'points.json'), '--bands', '3', '-q'];
writeFileSync(join(work, 'points.json'), JSON.stringify([[0.9, 0.5, 0.9]]));
run(prt, ['probes', ...common, '--format', 'threejs', '-o', join(work, 'probe.json')]);
run(prt, ['probes', ...common, '--format', 'prt', '-o', join(work, 'probe.prtprobes')]);
const referenceReport = run(referenceTool, [join(work, 'probe.prtprobes'), '0', String(albedo), String(size), join(work, 'reference.rgba')]);
const reference = readFileSync(join(work, 'reference.rgba'));

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
  await page.goto(`http://127.0.0.1:${port}/index.html?file=/work/probe.json&probe=0&albedo=${albedo}&size=${size}`);
  await page.waitForFunction(() => window.prtReady === true || window.prtError, null, { timeout: 60000 }).catch(() => {});
  const ready = await page.evaluate(() => window.prtReady === true);
  if (!ready) throw new Error(`the page did not render: ${errors.join('; ') || 'timeout'}`);
  const info = await page.evaluate(() => window.prtProbe);
  const shot = decodePng(await page.locator('canvas').screenshot());
  if (shot.width !== size || shot.height !== size) throw new Error(`screenshot is ${shot.width}x${shot.height}, expected ${size}x${size}`);
  writeFileSync(join(work, 'screenshot.rgba'), shot.pixels);
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
  console.log(`three.js r${info.three}, probe ${info.index}; reference: ${referenceReport.trim()}`);
  console.log(`compared ${compared} pixels: mean |difference| ${mean.toFixed(4)} levels, max ${worst} levels${worst ? ' at ' + worstAt : ''}`);
  if (compared < 0.5 * size * size || worst > 2 || mean > 0.5) {
    failed = true;
    console.log('FAIL: the page does not show the lighting prt computed (tolerance: max 2 levels, mean 0.5)');
  } else {
    console.log('PASS');
  }
} catch (e) {
  failed = true;
  console.error(`FAIL: ${e.message}`);
} finally {
  await context.close();
  server.close();
  rmSync(profile, { recursive: true, force: true });
}
process.exit(failed ? 1 : 0);
