// The lightmap glTF of `prt bake --lightmap --gltf` (docs/formats.md, "Lightmap transfer in glTF") as
// engines' tools see it: the Khronos glTF validator reports no errors (and, as warnings, only that it
// does not know the KTX2 images: this validator predates KHR_texture_basisu); ktx-parse (the KTX2
// reader of three.js and glTF-Transform) reads each texture as an RGBA16F 2D array of the file's size;
// and its float16 texels, decoded here, equal the .prt's values (read here from docs/formats.md's layout,
// not with prt's reader) to float16 rounding, the padding zero.
// Usage: node test_lightmap_gltf.mjs --dir DIR --names A[,B...]  (checks DIR/A.glb against DIR/A.prt, ...)
import { readFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { join } from 'node:path';
import { read as readKtx } from 'ktx-parse';
import { Checker, argument } from './common.mjs';

const require = createRequire(import.meta.url);
const validator = require('gltf-validator');
const check = new Checker('engines_lightmap_gltf');
const kinds = ['unshadowed', 'shadowed', 'interreflected'];

// IEEE binary16 to a number.
function half(bits) {
  const sign = bits & 0x8000 ? -1 : 1, exponent = (bits >> 10) & 0x1f, fraction = bits & 0x3ff;
  if (exponent === 0) return sign * fraction * 2 ** -24;
  if (exponent === 31) return fraction ? NaN : sign * Infinity;
  return sign * (1 + fraction / 1024) * 2 ** (exponent - 15);
}

// A texel .prt (versions 3, 4) by formats.md: header, parameters, padding, texel block, header
// checksum, then the coverage mask (padded to 8) and the sections.
function readTexelPrt(path) {
  const b = readFileSync(path);
  if (b.toString('latin1', 0, 8) !== 'PRTXFER\0') throw new Error(`${path}: not a .prt`);
  const version = b.readUInt32LE(8);
  if (version !== 3 && version !== 4) throw new Error(`${path}: version ${version} is not a texel file`);
  const p = { version, kind: b.readUInt32LE(12), bands: b.readUInt32LE(16), channels: b.readUInt32LE(24), scalar: b.readUInt32LE(28) };
  const parameters = b.readUInt32LE(72);
  const t = Math.ceil((76 + parameters) / 8) * 8;
  p.width = b.readUInt32LE(t);
  p.height = b.readUInt32LE(t + 4);
  let at = t + 24 + 8;  // the header checksum, then the payload
  const texels = p.width * p.height;
  p.coverage = b.subarray(at, at + texels);
  at += Math.ceil(texels / 8) * 8;
  p.perTexel = p.channels * p.bands * p.bands;
  const size = p.scalar === 1 ? 2 : 4;
  const section = (offset) => Float64Array.from({ length: texels * p.perTexel },
    (_, k) => (p.scalar === 1 ? half(b.readUInt16LE(offset + 2 * k)) : b.readFloatLE(offset + 4 * k)));
  p.sections = [section(at)];
  if (version === 4) p.sections.push(section(at + texels * p.perTexel * size));
  if (at + p.sections.length * texels * p.perTexel * size !== b.length) throw new Error(`${path}: payload size does not match`);
  return p;
}

async function checkPair(glbPath, prtPath) {
  const bytes = readFileSync(glbPath);
  const report = await validator.validateBytes(new Uint8Array(bytes), { uri: glbPath, maxIssues: 200 });
  const errors = report.issues.messages.filter((m) => m.severity === 0);
  check.check(`${glbPath}: 0 validator errors`, report.issues.numErrors === 0,
              `${report.issues.numErrors} errors: ${errors.slice(0, 5).map((m) => `${m.code} ${m.pointer || ''} ${m.message}`).join('; ')}`);
  const warnings = report.issues.messages.filter((m) => m.severity === 1);
  const known = (m) => /^\/images\/\d+(\/mimeType)?$/.test(m.pointer || '') && ['VALUE_NOT_IN_LIST', 'IMAGE_UNRECOGNIZED_FORMAT'].includes(m.code);
  check.check(`${glbPath}: warnings only about the KTX2 images`, warnings.every(known),
              warnings.filter((m) => !known(m)).map((m) => `${m.code} ${m.pointer}`).join('; '));
  console.log(`${glbPath}: ${report.issues.numErrors} errors, ${report.issues.numWarnings} warnings, ${report.issues.numInfos} infos`);

  const jsonLength = bytes.readUInt32LE(12);
  const doc = JSON.parse(bytes.toString('utf8', 20, 20 + jsonLength));
  const bin = bytes.subarray(20 + jsonLength + 8);
  const primitive = doc.meshes[0].primitives[0];
  const ext = (primitive.extensions || {}).PRT_lightmap_transfer;
  check.check(`${glbPath}: PRT_lightmap_transfer on the primitive, used and not required`,
              ext && doc.extensionsUsed.includes('PRT_lightmap_transfer') && !(doc.extensionsRequired || []).includes('PRT_lightmap_transfer'));
  if (!ext) return;
  check.check(`${glbPath}: TEXCOORD_${ext.texCoord} present`, `TEXCOORD_${ext.texCoord}` in primitive.attributes);
  const prt = readTexelPrt(prtPath);
  check.check(`${glbPath}: extension fields match the .prt`,
              ext.kind === kinds[prt.kind] && ext.bands === prt.bands && ext.channels === prt.channels && ext.width === prt.width &&
              ext.height === prt.height && ext.layers === Math.ceil(prt.perTexel / 4) && (prt.version === 4) === ('bounceOnly' in ext),
              JSON.stringify(ext));
  const images = [ext.transfer].concat('bounceOnly' in ext ? [ext.bounceOnly] : []);
  images.forEach((image, s) => {
    const view = doc.bufferViews[doc.images[image].bufferView];
    const ktx = readKtx(new Uint8Array(bin.buffer, bin.byteOffset + (view.byteOffset || 0), view.byteLength));
    const name = `${glbPath} image ${image}`;
    check.check(`${name}: KTX2 R16G16B16A16_SFLOAT 2D array, ${prt.width}x${prt.height}, ${ext.layers} layers, 1 level, uncompressed`,
                ktx.vkFormat === 97 && ktx.typeSize === 2 && ktx.pixelWidth === prt.width && ktx.pixelHeight === prt.height &&
                ktx.pixelDepth === 0 && ktx.layerCount === ext.layers && ktx.faceCount === 1 && ktx.levels.length === 1 &&
                ktx.supercompressionScheme === 0 && doc.images[image].mimeType === 'image/ktx2',
                `${ktx.vkFormat} ${ktx.pixelWidth}x${ktx.pixelHeight}x${ktx.pixelDepth} layers ${ktx.layerCount}`);
    const level = ktx.levels[0].levelData, texels = prt.width * prt.height;
    if (level.byteLength !== texels * ext.layers * 8) { check.check(`${name}: level size`, false); return; }
    const data = new DataView(level.buffer, level.byteOffset, level.byteLength);
    let worst = 0, padding = true;
    for (let layer = 0; layer < ext.layers; layer++)
      for (let texel = 0; texel < texels; texel++)
        for (let c = 0; c < 4; c++) {
          const got = half(data.getUint16(((layer * texels + texel) * 4 + c) * 2, true)), value = 4 * layer + c;
          if (value >= prt.perTexel) { padding = padding && got === 0; continue; }
          const want = prt.sections[s][texel * prt.perTexel + value];
          // float16 rounding: half an ulp, 2^-11 relative, 2^-25 absolute below the normal range.
          worst = Math.max(worst, Math.abs(got - want) / (Math.abs(want) * 2 ** -11 + 2 ** -25));
        }
    check.check(`${name}: every texel's values to float16 rounding of the .prt (worst ${worst.toFixed(3)} half-ulps)`, worst <= 1);
    check.check(`${name}: padding components are 0`, padding);
  });
}

const dir = argument('dir');
for (const name of argument('names').split(',')) await checkPair(join(dir, `${name}.glb`), join(dir, `${name}.prt`));
check.finish();
