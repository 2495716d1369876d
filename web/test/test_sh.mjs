// web/sh.js against the real `prt` binary, in node with three.js's own loaders (EXRLoader, RGBELoader,
// through their load() path, so the texture's data, type and flipY are what three gives a page):
//  1. projection: web/sh.js's projection of an equirect map equals `prt light --sun none --window none`
//     within 1e-4 of c0 (the red/green/blue c0 of the map; every coefficient, every channel), for two
//     real HDRIs (assets/env, CC0) as float EXR and half-float EXR, and for an RGBE .hdr written here
//     (flat scanlines, a smooth sky with a bright spot, exponents spread over 2^-3 .. 2^4);
//  2. run-time band truncation: sh.js's truncateBands of the 5-band projection to 3 bands equals
//     `prt light --bands 3` (zero beyond) within 1e-4 of c0;
//  3. rotation: sh.js's rotation of that projection by R(yaw, pitch, roll) equals
//     `prt light --rotate YAW,PITCH,ROLL` (prt rotates with the Ivanic-Ruedenberg recursion in C++; sh.js
//     integrates Y_i(d) Y_j(R^T d) by quadrature: no shared code) within 1e-4 of c0.
// Usage: node web/test/test_sh.mjs --prt <prt binary> --env <a.exr,b.exr> [--work DIR]
// Exit status 0 pass, 1 fail.
import { mkdirSync, mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { basename, join } from 'node:path';
import { FloatType, HalfFloatType } from 'three';
import { EXRLoader } from 'three/examples/jsm/loaders/EXRLoader.js';
import { RGBELoader } from 'three/examples/jsm/loaders/RGBELoader.js';
import { argument, run } from '../../tests/engines/common.mjs';
import { projectEquirect, rotateRgb, rotationFromYawPitchRoll, shRotation, truncateBands } from '../sh.js';

// three's FileLoader reports progress with the DOM's ProgressEvent, which node lacks.
globalThis.ProgressEvent ??= class extends Event { constructor(type, init) { super(type); Object.assign(this, init); } };

const prt = argument('prt');
const work = argument('work', mkdtempSync(join(tmpdir(), 'prt-web-sh-')));
mkdirSync(work, { recursive: true });
const bands = 5;
let failed = false;

function loadTexture(Loader, path, type) {
  const url = `data:application/octet-stream;base64,${readFileSync(path).toString('base64')}`;
  return new Promise((ok, fail) => new Loader().setDataType(type).load(url, ok, undefined, fail));
}

function writeRgbe(path, width, height) {
  const header = Buffer.from(`#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y ${height} +X ${width}\n`, 'ascii');
  const pixels = Buffer.alloc(4 * width * height);
  for (let j = 0; j < height; j++) {
    for (let i = 0; i < width; i++) {
      const t = Math.PI * (j + 0.5) / height, p = 2 * Math.PI * (i + 0.5) / width;
      const rgb = [0.3 + 0.2 * Math.cos(t), 0.5 + 0.4 * Math.sin(p) * Math.sin(t), 0.9 - 0.5 * Math.cos(t)]
        .map((v, c) => v * (1 + 15 * Math.exp(-40 * ((t - 0.8) ** 2 + (p - 2 - 0.3 * c) ** 2))));
      const e = Math.ceil(Math.log2(Math.max(...rgb)) + 1e-9);
      const o = 4 * (j * width + i);
      rgb.forEach((v, c) => { pixels[o + c] = Math.min(255, Math.floor(v / 2 ** e * 256)); });
      pixels[o + 3] = e + 128;
    }
  }
  writeFileSync(path, Buffer.concat([header, pixels]));
}

function prtLight(path, extra, lightBands = bands) {
  const out = join(work, `${basename(path)}${extra.join('_').replace(/[^a-z0-9_]/gi, '')}_${lightBands}.json`);
  run(prt, ['light', path, '--bands', String(lightBands), '--sun', 'none', '--window', 'none', ...extra, '-o', out]);
  return Float64Array.from(JSON.parse(readFileSync(out, 'utf8')).coefficients.flat());
}

function compare(what, got, expected, bound = 1e-4) {
  const c0 = Math.max(Math.abs(expected[0]), Math.abs(expected[1]), Math.abs(expected[2]));
  let worst = 0, at = 0;
  for (let i = 0; i < expected.length; i++) {
    const d = Math.abs(got[i] - expected[i]);
    if (d > worst) { worst = d; at = i; }
  }
  const ok = worst <= bound * c0 && got.length === expected.length;
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}: max |sh.js - prt| = ${worst.toExponential(3)} = ${(worst / c0).toExponential(3)} c0 ` +
              `(coefficient ${Math.floor(at / 3)} channel ${at % 3}; bound ${bound} c0)`);
  if (!ok) failed = true;
}

// Writes an uncompressed scanline float EXR (channels B, G, R; one line per block) of a three.js
// equirect texture's pixels as three decoded them (rows flipped back to top-first, values as they are,
// negatives included): prt (OpenEXR) and three (EXRLoader) then read the same floats.
function writeFloatExr(path, texture) {
  const { data, width, height } = texture.image;
  const channels = data.length / (width * height);
  const attribute = (name, type, value) => Buffer.concat([Buffer.from(`${name}\0${type}\0`, 'latin1'), int32(value.length), value]);
  const int32 = (...v) => { const b = Buffer.alloc(4 * v.length); v.forEach((x, i) => b.writeInt32LE(x, 4 * i)); return b; };
  const float32 = (...v) => { const b = Buffer.alloc(4 * v.length); v.forEach((x, i) => b.writeFloatLE(x, 4 * i)); return b; };
  const channel = (name) => Buffer.concat([Buffer.from(`${name}\0`), int32(2), Buffer.from([0, 0, 0, 0]), int32(1, 1)]);
  const header = Buffer.concat([
    Buffer.from([0x76, 0x2f, 0x31, 0x01]), int32(2),
    attribute('channels', 'chlist', Buffer.concat([channel('B'), channel('G'), channel('R'), Buffer.from([0])])),
    attribute('compression', 'compression', Buffer.from([0])),
    attribute('dataWindow', 'box2i', int32(0, 0, width - 1, height - 1)),
    attribute('displayWindow', 'box2i', int32(0, 0, width - 1, height - 1)),
    attribute('lineOrder', 'lineOrder', Buffer.from([0])),
    attribute('pixelAspectRatio', 'float', float32(1)),
    attribute('screenWindowCenter', 'v2f', float32(0, 0)),
    attribute('screenWindowWidth', 'float', float32(1)),
    Buffer.from([0])]);
  const blockSize = 8 + 12 * width;
  const offsets = Buffer.alloc(8 * height);
  const blocks = Buffer.alloc(blockSize * height);
  for (let y = 0; y < height; y++) {
    offsets.writeBigUInt64LE(BigInt(header.length + offsets.length + y * blockSize), 8 * y);
    const o = y * blockSize, row = texture.flipY ? y : height - 1 - y;
    blocks.writeInt32LE(y, o);
    blocks.writeInt32LE(12 * width, o + 4);
    for (let c = 0; c < 3; c++) {
      for (let x = 0; x < width; x++) blocks.writeFloatLE(data[(row * width + x) * channels + (2 - c)], o + 8 + 4 * (c * width + x));
    }
  }
  writeFileSync(path, Buffer.concat([header, offsets, blocks]));
}

// The bundled HDRIs are DWAB-compressed (lossy): three's EXRLoader decodes them up to 112 away from
// OpenEXR on a sun texel of 33664 (mean 6e-4 per value), so their projections differ by ~1e-3 c0
// before any SH code runs. The exact comparison therefore reads a lossless float EXR of the same
// pixels (written above); the DWAB file itself is held to 3e-3 c0 (the decoders' difference).
// The first map gets every check; the others the lossless projection (each check runs `prt light`).
const rotations = [[30, 40, 50], [-120, 75, 10]];
for (const [index, path] of argument('env').split(',').entries()) {
  const original = await loadTexture(EXRLoader, path, FloatType);
  if (index === 0) compare(`projection of ${basename(path)} (DWAB, three's decoder against OpenEXR's)`, projectEquirect(original, bands), prtLight(path, []), 3e-3);
  const lossless = join(work, basename(path).replace(/\.exr$/, '_float.exr'));
  writeFloatExr(lossless, original);
  for (const type of index === 0 ? [FloatType, HalfFloatType] : [FloatType]) {
    const texture = await loadTexture(EXRLoader, lossless, type);
    const name = `${basename(lossless)} (EXRLoader, ${type === FloatType ? 'FloatType' : 'HalfFloatType'}, flipY ${texture.flipY})`;
    const projected = projectEquirect(texture, bands);
    // (The DWAB files hold half floats, so three's HalfFloatType gives the same values.)
    compare(`projection of ${name}`, projected, prtLight(lossless, []));
    if (type === HalfFloatType || index > 0) continue;
    // Run-time band truncation (PrtRelighting.setBands): the 5-band projection cut to 3 bands is prt's own
    // 3-band projection, zero beyond (coefficients 9..24); a rule that dropped band 2 too, or kept band 3, fails.
    const three = prtLight(lossless, [], 3);
    compare(`truncation of ${name} to 3 bands`, truncateBands(projected, 3),
            Float64Array.from({ length: 3 * bands * bands }, (_, i) => (i < three.length ? three[i] : 0)));
    for (const [y, p, r] of rotations) {
      const rotated = rotateRgb(projected, shRotation(bands, rotationFromYawPitchRoll(y, p, r)));
      compare(`rotation ${y},${p},${r} of ${name}`, rotated, prtLight(lossless, ['--rotate', `${y},${p},${r}`]));
    }
  }
}
// RGBE: three's RGBELoader decodes a mantissa m as m/255 2^(e-128); prt (OpenImageIO, Radiance's
// rgbe2float) as m/256 2^(e-128). projectEquirect's {rgbe: true} option undoes three's factor 256/255.
const hdr = join(work, 'smooth.hdr');
writeRgbe(hdr, 128, 64);
const rgbe = await loadTexture(RGBELoader, hdr, FloatType);
compare(`projection of ${basename(hdr)} (RGBELoader, flipY ${rgbe.flipY}, rgbe: true)`, projectEquirect(rgbe, bands, { rgbe: true }), prtLight(hdr, []));
console.log(failed ? 'FAIL' : 'PASS');
process.exit(failed ? 1 : 0);
