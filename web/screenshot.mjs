// Retakes web/viewer.png (the README's picture of the viewer) from the repository's own assets, headless:
// bakes the bundled lion (assets/meshes/guardian_lion_10k.ply, 5-band interreflected transfer, the engine
// glTF), lights it with the bundled sunrise.exr (`prt light`: its SH and its sun as a disc), opens
// web/viewer.html in headless Chromium (web/test/browser.mjs) and saves the page, control panel and
// status line included.
// Usage: node web/screenshot.mjs --prt <prt> [--out web/viewer.png] [--size 640x360] [--work DIR]
// (a --work folder that already holds guardian_lion.glb and sunrise.json is not baked again).
import { existsSync, mkdirSync, mkdtempSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import { argument, run } from '../tests/engines/common.mjs';
import { openPage, repoRoot, requireBrowser, runInBrowser } from './test/browser.mjs';

requireBrowser();
const prt = argument('prt');
const out = resolve(argument('out', join(repoRoot, 'web', 'viewer.png')));
const [width, height] = argument('size', '640x360').split('x').map(Number);
if (!(width >= 64 && height >= 64)) throw new Error(`--size ${argument('size')}: expected WxH, at least 64x64`);
const work = resolve(argument('work', mkdtempSync(join(tmpdir(), 'prt-web-screenshot-'))));
mkdirSync(work, { recursive: true });

const mesh = join(repoRoot, 'assets', 'meshes', 'guardian_lion_10k.ply'), sky = join(repoRoot, 'assets', 'env', 'sunrise.exr');
const baked = existsSync(join(work, 'guardian_lion.glb')) && existsSync(join(work, 'sunrise.json'));
if (!baked) run(prt, ['bake', mesh, '--transfer', 'interreflected', '--bands', '5', '-q', '-o', join(work, 'guardian_lion.prt'),
          '--gltf', join(work, 'guardian_lion.glb')]);
if (!baked) run(prt, ['light', sky, '--bands', '5', '-o', join(work, 'sunrise.json')]);

await runInBrowser(work, width, height, async ({ port, context }) => {
  const page = await openPage(context, `http://127.0.0.1:${port}/web/viewer.html?glb=/work/guardian_lion.glb&env=/work/sunrise.json` +
                                       '&sky=/assets/env/sunrise.exr&camera=35,15,auto&exposure=-1.5&tonemap=aces', 'prtViewerReady');
  await page.evaluate(() => window.prtViewer.renderNow());
  await page.screenshot({ path: out });
  console.log(`${out}: ${width}x${height}; status line: ${await page.locator('#status').innerText()}`);
  if (page.errors.length) console.log(`page errors: ${page.errors.join('; ')}`);
  return page.errors.length > 0;
});
