// Acceptance test of the three.js runtime (web/prt_transfer.js) in headless Chromium with the real
// three.js of web/package-lock.json: its pixels against `prt render`'s for the same bake, camera and
// lighting. Both sides render linear radiance (prt: EXR; the page: a float render target), and the
// comparison runs over the object's pixels (the page's coverage, less the 1-pixel rim of silhouettes,
// creases and depth steps where the two rasterisers may pick different triangles; compareImages):
// rel_rms = sqrt(sum |a - b|^2 / sum |b|^2) <= 1%, and the 99th percentile of |a - b| / rms(b) is printed.
//
// Cases (each: a bake's engine glTF from `prt bake --gltf`, a `prt light` JSON, camera, rotation, sun):
// per-vertex interreflected transfer of a sphere on a floor with the sun off, a 2-degree disc, the map's
// own sun and a rotated environment; a textured glTF (BoxTextured: base colour texture per pixel, the
// albedo split); a glTF of many nodes with their transforms and instanced meshes (2CylinderEngine, when
// Debian's assimp-testmodels is installed); a lightmap (per-texel transfer, the per-texel PRT_transfer form). Every
// export has at most 16 vertex attributes; a mixed scene (per-texel floor and wall, a per-vertex box, one
// engine glTF) against prt render of its .prt pair.
//
// Usage: node web/test/test_runtime.mjs --prt <prt> --env <sky.exr> --mesh <mesh> --textured <glTF>
//        [--nodes <glTF>] [--mixed-asset <ClearCoatTest.gltf>] [--work DIR]
//        [--dump DIR] (PPM images of each case); PRT_ONLY=<text> runs the cases whose name contains it
//        [--break order|rotation|albedo|mips|model]  (a deliberately wrong runtime: swapped SH coefficients, no rotation,
//                                   the lightmap's _PRT_ALBEDO dropped or its level 0 alone sampled,
//                                   a mixed scene's per-vertex primitives shaded with model 0;
//                                   the test must then fail)
// Exit status 0 pass, 1 fail, 77 skipped (no Chromium).
import { existsSync, mkdirSync, mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import { FloatType } from 'three';
import { EXRLoader } from 'three/examples/jsm/loaders/EXRLoader.js';
import { argument, run } from '../../tests/engines/common.mjs';
import { openPage, requireBrowser, runInBrowser } from './browser.mjs';
import { bakeGlb, prepareBake } from './bake_fixture.mjs';
import { writeLightmapScene, writeMixedScene } from './lightmap_scene.mjs';

requireBrowser();
const prt = argument('prt');
const env = resolve(argument('env'));
const mesh = resolve(argument('mesh'));
const work = resolve(argument('work', mkdtempSync(join(tmpdir(), 'prt-web-runtime-'))));
const breakage = argument('break', '');
const dump = argument('dump', '');  // a folder: writes each case's page, prt and |difference| x 10 as PPM
mkdirSync(work, { recursive: true });
const defaultSize = 256;
const bands = 3;

const bake = prepareBake({ prt, mesh, env, work, bands });
// The other bakes, each made when a case that is run first needs it (a broken page's run needs one).
const once = (make) => { let made; return () => (made ??= make()); };
const texturedPath = resolve(argument('textured')), nodesPath = resolve(argument('nodes', '/nonexistent'));
if (!existsSync(texturedPath)) throw new Error(`${texturedPath}: the textured glTF is missing`);
const textured = once(() => bakeGlb({ prt, mesh: texturedPath, work, name: 'textured', samples: 64 }));
const nodes = once(() => bakeGlb({ prt, mesh: nodesPath, work, name: 'nodes', samples: 16 }));
// Per texel: a 64 x 64 lightmap of a floor and a box (web/test/lightmap_scene.mjs), `prt bake --lightmap --gltf`.
const lightmapObj = writeLightmapScene(work);
const lightmap = once(() => bakeGlb({ prt, mesh: lightmapObj, work, name: 'lightmap', samples: 64, extra: ['--lightmap', '64x64'] }));
// A lightmap seen minified (a 256 x 256 lightmap, 16 samples: noisy texels, in a 64 x 64 image): prt
// render and the runtime sample the coverage-aware mip chain trilinearly; level 0 alone would alias.
const farLightmap = once(() => bakeGlb({ prt, mesh: lightmapObj, work, name: 'lightmap_far', samples: 16, extra: ['--lightmap', '256x256'] }));
// A textured lightmap: BoxTextured per texel on generated lightmap UVs. Its transfer holds the texture's
// colour per texel; the sun's direct light takes the bake's per-vertex albedo (the texture's footprint
// averages, _PRT_ALBEDO), as prt render does, not the material's white factor.
const texturedLightmap = once(() => bakeGlb({ prt, mesh: texturedPath, work, name: 'textured_lightmap', samples: 64,
                                               extra: ['--lightmap', '64x64', '--uv', 'generate'] }));
// A mixed scene (web/test/lightmap_scene.mjs: Floor and Wall per texel, Box per vertex, one glTF): its
// engine glTF draws both kinds in one scene, each primitive with its own model; prt renders the .prt pair.
const mixedScene = writeMixedScene(work);
const mixed = once(() => bakeGlb({ prt, mesh: mixedScene, work, name: 'mixed', samples: 64,
                                   extra: ['--lightmap', '64x64', '--texel-parts', 'Floor,Wall'] }));
// A real mixed scene: Khronos's ClearCoatTest (CC-BY 4.0, from Debian's assimp-testmodels when installed),
// its nine two-sided label planes per texel on generated UVs (their own UVs overlap), its 18 spheres per
// vertex; prt renders the pair with the mesh that carries the UVs, ROOM.mesh.glb.
const clearCoatPath = resolve(argument('mixed-asset', '/nonexistent'));
const clearCoatLabels = 'X0_Label_BaseLayer,X1_Label_Coated,X2_Label_CoatingOnly,Y0_Label_SimpleCoating,Y1_Label_PartialCoating,' +
                        'Y2_Label_Roughness,Y3_Label_BaseNormals,Y4_Label_CoatNormals,Y5_Label_SharedNormals';
const clearCoat = once(() => bakeGlb({ prt, mesh: clearCoatPath, work, name: 'clearcoat', samples: 32,
                                       extra: ['--lightmap', '128', '--uv', 'auto', '--texel-parts', clearCoatLabels] }));
const plain = () => bake.glb;

const cases = [
  { name: 'sun off', glb: plain, light: 'sky.json', camera: [30, 25], rotate: [0, 0, 0], sun: false },
  { name: 'sun on (a 2-degree disc high in the sky: PCSS shadow, bounce)', glb: plain, light: 'disc.json', camera: [30, 25], rotate: [0, 0, 0], sun: true },
  { name: 'sun on (the map\'s own sun, found by prt light)', glb: plain, light: 'sun.json', camera: [30, 25], rotate: [0, 0, 0], sun: true },
  { name: 'rotated environment, sun on', glb: plain, light: 'disc.json', camera: [-40, 30], rotate: [70, 20, 0], sun: true },
  { name: 'textured glTF (BoxTextured), sun on', glb: textured, light: 'disc.json', camera: [35, 30], rotate: [20, 0, 0], sun: true },
  { name: 'lightmap (per texel), sun off', glb: lightmap, render: [lightmapObj, join(work, 'lightmap.prt')], light: 'sky.json', camera: [30, 35], rotate: [40, 0, 0], sun: false },
  { name: 'lightmap (per texel), sun on', glb: lightmap, render: [lightmapObj, join(work, 'lightmap.prt')], light: 'disc.json', camera: [30, 35], rotate: [40, 0, 0], sun: true },
  { name: 'lightmap seen minified (mip chain), sun off', glb: farLightmap, light: 'sky.json', camera: [30, 35], rotate: [40, 0, 0], sun: false, size: 64 },
  { name: 'textured lightmap (BoxTextured, generated UVs), sun on', glb: texturedLightmap, light: 'disc.json', camera: [35, 30], rotate: [20, 0, 0], sun: true },
  { name: 'mixed scene (Floor, Wall per texel; Box per vertex), sun off', glb: mixed, render: [mixedScene, join(work, 'mixed.prt')], light: 'sky.json',
    camera: [20, 30], rotate: [30, 0, 0], sun: false },
  { name: 'mixed scene (Floor, Wall per texel; Box per vertex), sun on', glb: mixed, render: [mixedScene, join(work, 'mixed.prt')], light: 'disc.json',
    camera: [20, 30], rotate: [30, 0, 0], sun: true },
  ...(existsSync(clearCoatPath) ? [{ name: 'mixed real scene (ClearCoatTest: labels per texel, generated UVs; spheres per vertex), sun on', glb: clearCoat,
                                     render: [join(work, 'clearcoat.mesh.glb'), join(work, 'clearcoat.prt')], light: 'disc.json', camera: [0, 10],
                                     rotate: [0, 0, 0], sun: true }] : []),
  ...(existsSync(nodesPath) ? [{ name: 'glTF with many nodes (2CylinderEngine), sun on', glb: nodes, light: 'disc.json', camera: [10, 30], rotate: [0, 0, 0], sun: true }] : []),
];

// A deliberately broken page needs only the cases it must fail: the plain one (coefficient order), the
// rotated ones (missing rotation), the textured lightmap (no _PRT_ALBEDO), the minified lightmap (no mips).
if (process.env.PRT_ONLY) cases.splice(0, cases.length, ...cases.filter((c) => c.name.includes(process.env.PRT_ONLY)));
const broken = { order: (c) => c === cases[0], rotation: (c) => c.rotate.some((v) => v !== 0), albedo: (c) => c.name.startsWith('textured lightmap'),
                 mips: (c) => c.name.includes('(mip chain)'), model: (c) => c.name.startsWith('mixed') };
if (breakage) cases.splice(0, cases.length, ...cases.filter(broken[breakage]));

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

/// rel_rms and the 99th percentile of |a - b| / rms(b) over the object's pixels: covered (alpha 1 in the
/// page's image) together with all 8 neighbours, and on the same surface as them (the page's
/// `surface` buffer: triangle-plane normals within 2.6 degrees, view depths within depthTolerance: 1% at
/// 256 pixels across, as much more as a smaller image's pixels are larger). The rest is the
/// rim where two rasterisers may cover a pixel with different triangles: silhouettes, creases, parts
/// in front of others.
export function compareImages(page, reference, width, height, surface, depthTolerance = 0.01) {
  const covered = (x, y) => x >= 0 && y >= 0 && x < width && y < height && page[4 * (y * width + x) + 3] > 0.5;
  const same = (i, j) => surface[4 * i] * surface[4 * j] + surface[4 * i + 1] * surface[4 * j + 1] + surface[4 * i + 2] * surface[4 * j + 2] > 0.999 &&
                         Math.abs(surface[4 * i + 3] - surface[4 * j + 3]) < depthTolerance * surface[4 * i + 3];
  const diffs = [];
  let sumSq = 0, refSq = 0;
  for (let y = 0; y < height; y++) for (let x = 0; x < width; x++) {
    let inside = true;
    for (let dy = -1; dy <= 1; dy++) for (let dx = -1; dx <= 1; dx++) inside = inside && covered(x + dx, y + dy) && same(y * width + x, (y + dy) * width + x + dx);
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

// Binary PPMs (clamped linear values x 255) of the page's image, prt's and 10 |page - prt|, side by side.
function dumpImages(prefix, page, reference, size) {
  const out = Buffer.alloc(3 * 3 * size * size);
  for (let y = 0; y < size; y++) for (let x = 0; x < size; x++) for (let c = 0; c < 3; c++) {
    const a = page[4 * (y * size + x) + c], b = reference[3 * (y * size + x) + c];
    [a, b, 10 * Math.abs(a - b)].forEach((v, k) => { out[3 * (y * 3 * size + k * size + x) + c] = Math.max(0, Math.min(255, Math.round(255 * v))); });
  }
  writeFileSync(`${prefix}.ppm`, Buffer.concat([Buffer.from(`P6 ${3 * size} ${size} 255\n`), out]));
}

await runInBrowser(work, defaultSize, defaultSize, async ({ port, context }) => {
  let failed = false;
  const page = await openPage(context, `http://127.0.0.1:${port}/web/test/harness.html${breakage ? `?break=${breakage}` : ''}`, 'prtHarnessReady');
  for (const c of cases) {
    const size = c.size || defaultSize;
    const reference = join(work, `reference_${cases.indexOf(c)}.exr`);
    const glbName = c.glb();
    const glb = join(work, glbName);
    run(prt, ['render', ...(c.render || [glb, glb]), '--env', join(work, c.light), '--window', 'none',
              '--background', 'black', '--size', `${size}x${size}`, '--camera', `${c.camera[0]},${c.camera[1]},${c.camera[2] || 'auto'}`,
              '--rotate', c.rotate.join(','), '--sun', c.sun ? 'auto' : 'none', '-o', reference]);
    await page.reload();
    await page.waitForFunction(() => window.prtHarnessReady === true);
    const info = await page.evaluate((a) => window.prtLoad(a), { glb: `/work/${glbName}`, light: `/work/${c.light}` });
    const shot = await page.evaluate((a) => window.prtRender(a), { width: size, height: size, camera: { azimuth: c.camera[0], elevation: c.camera[1], distance: c.camera[2] || 'auto' },
                                                                  rotate: c.rotate, sun: c.sun });
    const pixels = new Float32Array(Buffer.from(shot.pixels, 'base64').buffer.slice(0));
    const ref = readExr(reference);
    const surface = new Float32Array(Buffer.from(shot.surface, 'base64').buffer.slice(0));
    const r = compareImages(pixels, ref.pixels, size, size, surface, 0.01 * defaultSize / size);  // depth steps scale with the pixel
    if (dump) dumpImages(join(dump, `case${cases.indexOf(c)}`), pixels, ref.pixels, size);
    const ok = r.relRms <= 0.01 && r.pixels > 0.05 * size * size && info.maxAttributes <= 16 && page.errors.length === 0;
    console.log(`${ok ? 'ok  ' : 'FAIL'} ${c.name}: rel_rms ${(100 * r.relRms).toFixed(3)}% over ${r.pixels} pixels ` +
                `(bound 1%); 99th percentile |error| ${(100 * r.p99).toFixed(2)}% of rms, max ${(100 * r.max).toFixed(1)}%; ` +
                `${info.maxAttributes} vertex attributes (MAX_VERTEX_ATTRIBS ${info.gl}); three r${info.three}`);
    if (page.errors.length) console.log(`  page errors: ${page.errors.join('; ')}`);
    if (!ok) failed = true;
  }
  return failed;
});
