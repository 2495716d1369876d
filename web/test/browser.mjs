// Headless Chromium (Debian's /usr/bin/chromium through playwright-core from web/node_modules) and a
// loopback HTTP server for the web/ tests: the repository root at /, a work folder at /work/.
import { existsSync, mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { createServer } from 'node:http';
import { tmpdir } from 'node:os';
import { dirname, extname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

export const webRoot = resolve(dirname(fileURLToPath(import.meta.url)), '..');
export const repoRoot = resolve(webRoot, '..');
export const chromiumPath = '/usr/bin/chromium';

/// Exits 77 (ctest: skipped) when Chromium is missing, 1 when web/node_modules is.
export function requireBrowser() {
  if (!existsSync(chromiumPath)) {
    console.log(`SKIP: ${chromiumPath} is not installed (Debian package 'chromium')`);
    process.exit(77);
  }
  if (!existsSync(join(webRoot, 'node_modules', 'three')) || !existsSync(join(webRoot, 'node_modules', 'playwright-core'))) {
    console.error(`${webRoot}/node_modules is missing: run 'npm ci' in ${webRoot}`);
    process.exit(1);
  }
}

const types = { '.html': 'text/html', '.js': 'text/javascript', '.mjs': 'text/javascript', '.json': 'application/json',
                '.png': 'image/png', '.glb': 'model/gltf-binary' };

/// Serves the repository and `work`; returns {port, close()}.
export async function serve(work) {
  const server = createServer((request, response) => {
    const url = new URL(request.url, 'http://127.0.0.1');
    const path = decodeURIComponent(url.pathname);
    const file = path.startsWith('/work/') ? join(work, path.slice(6)) : join(repoRoot, path);
    if (path === '/favicon.ico') return response.writeHead(204).end();
    if ((!file.startsWith(repoRoot) && !file.startsWith(work)) || !existsSync(file)) return response.writeHead(404).end();
    response.writeHead(200, { 'Content-Type': types[extname(file)] || 'application/octet-stream' });
    response.end(readFileSync(file));
  });
  await new Promise((ok) => server.listen(0, '127.0.0.1', ok));
  return { port: server.address().port, close: () => server.close() };
}

/// Starts headless Chromium (SwiftShader WebGL2); returns {context, close()}.
export async function launch(width, height) {
  const { chromium } = await import(join(webRoot, 'node_modules', 'playwright-core', 'index.mjs'));
  const profile = mkdtempSync(join(tmpdir(), 'prt-web-chromium-'));
  const context = await chromium.launchPersistentContext(profile, {
    executablePath: chromiumPath, headless: true, viewport: { width, height }, deviceScaleFactor: 1,
    args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking',
           '--disable-component-update', '--disable-sync', '--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
  });
  return { context, close: async () => { await context.close(); rmSync(profile, { recursive: true, force: true }); } };
}

/// Opens `url` in a new page, collecting page errors and console errors into page.errors.
export async function openPage(context, url, readyFlag) {
  const page = await context.newPage();
  page.errors = [];
  page.on('pageerror', (e) => page.errors.push(String(e)));
  page.on('console', (m) => { if (m.type() === 'error') page.errors.push(m.text()); });
  await page.goto(url);
  await page.waitForFunction((flag) => window[flag] === true || window.prtError, readyFlag, { timeout: 60000 }).catch(() => {});
  if (!(await page.evaluate((flag) => window[flag] === true, readyFlag))) throw new Error(`${url} did not load: ${page.errors.join('; ') || 'timeout'}`);
  return page;
}

/// Serves `work`, starts Chromium at width x height, runs `body({port, context})` (which returns true when
/// a check failed), then closes both, prints PASS or FAIL and exits with 0 or 1 (an exception fails).
export async function runInBrowser(work, width, height, body) {
  const server = await serve(work);
  const browser = await launch(width, height);
  let failed = false;
  try {
    failed = await body({ port: server.port, context: browser.context });
  } catch (e) {
    failed = true;
    console.error(`FAIL: ${e.stack || e.message}`);
  } finally {
    await browser.close();
    server.close();
  }
  console.log(failed ? 'FAIL' : 'PASS');
  process.exit(failed ? 1 : 0);
}
