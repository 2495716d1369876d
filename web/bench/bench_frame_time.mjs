// Frame time of the PRT material against three's MeshStandardMaterial with an environment map on the
// same mesh, in headless Chromium (SwiftShader: a CPU rasteriser, so compare ratios, not milliseconds),
// both in one run, frames interleaved (prt, standard, prt+sun, standard+sun, ...). Prints per variant
// the median, best and worst frame and the ratios PRT / standard.
// Usage: node web/bench/bench_frame_time.mjs --prt <prt> --mesh <mesh> --env <sky.exr> [--frames 30] [--size 512] [--work DIR]
import { mkdirSync, mkdtempSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import { argument } from '../../tests/engines/common.mjs';
import { openPage, requireBrowser, runInBrowser } from '../test/browser.mjs';
import { prepareBake } from '../test/bake_fixture.mjs';

requireBrowser();
const prt = argument('prt'), mesh = resolve(argument('mesh')), env = resolve(argument('env'));
const frames = Number(argument('frames', '30')), size = Number(argument('size', '512'));
const work = resolve(argument('work', mkdtempSync(join(tmpdir(), 'prt-web-bench-'))));
mkdirSync(work, { recursive: true });
const bake = prepareBake({ prt, mesh, env, work, bands: 5 });
await runInBrowser(work, size, size, async ({ port, context }) => {
  const page = await openPage(context, `http://127.0.0.1:${port}/web/bench/frame_time.html?glb=/work/${bake.glb}` +
                                               `&light=/work/sun.json&env=${encodeURI(env.replace(/.*\/assets\//, '/assets/'))}&size=${size}`, 'prtBenchReady');
  const r = await page.evaluate((n) => window.prtBench(n), frames);
  const stats = (t) => { const s = [...t].sort((a, b) => a - b); return { median: s[Math.floor(s.length / 2)], best: s[0], worst: s[s.length - 1] }; };
  const m = Object.fromEntries(Object.entries(r.times).map(([k, t]) => [k, stats(t)]));
  console.log(`three r${r.three}, ${r.renderer}, ${r.vertices} vertices, ${size}x${size}, ${frames} frames each`);
  for (const [k, s] of Object.entries(m)) console.log(`  ${k.padEnd(13)} median ${s.median.toFixed(2)} ms (best ${s.best.toFixed(2)}, worst ${s.worst.toFixed(2)})`);
  console.log(`  ratio PRT / standard: ${(m.prt.median / m.standard.median).toFixed(2)} (best frames ${(m.prt.best / m.standard.best).toFixed(2)}); ` +
              `with the sun: ${(m.prt_sun.median / m.standard_sun.median).toFixed(2)} (best ${(m.prt_sun.best / m.standard_sun.best).toFixed(2)})`);
  if (page.errors.length) console.log(`page errors: ${page.errors.join('; ')}`);
  return page.errors.length > 0;
});
