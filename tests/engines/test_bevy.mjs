// The Bevy export (a KTX2 irradiance volume) as a KTX2 reader sees it: ktx-parse (a KTX 2.0
// parser for JavaScript, independent of prt) reads the container, and its header, level index and data
// format descriptor must be what Bevy's irradiance volumes load (VK_FORMAT_R16G16B16A16_SFLOAT, 3D,
// (NX, 2 NY, 3 NZ), one level, no supercompression, linear BT.709 RGBA). The texels, decoded from
// float16, must hold prt's E/pi at the six axis normals of every valid probe in the order Bevy's shader
// reads them (texel (x, y + NY s, z + NZ a) = axis a, sign s), within float16 precision (1e-3).
// Bevy itself is Rust and does not run here: its sampling stays re-implemented in
// tests/probes/test_engine_exports.cpp.
// Usage: node test_bevy.mjs --work DIR (the engines_fixture output)
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { read, KHR_DF_MODEL_RGBSDA, KHR_DF_TRANSFER_LINEAR, KHR_DF_PRIMARIES_BT709 } from 'ktx-parse';
import { Checker, argument, fixtureFolders } from './common.mjs';

const work = argument('work');
const check = new Checker('engines_bevy');

function half(bits) {
  const e = (bits >> 10) & 31, m = bits & 1023, s = bits & 0x8000 ? -1 : 1;
  if (e === 0) return s * m * 2 ** -24;
  if (e === 31) return m ? NaN : s * Infinity;
  return s * (1 + m / 1024) * 2 ** (e - 15);
}

for (const { name, dir, truth } of fixtureFolders(work)) {
  const ktx = read(new Uint8Array(readFileSync(join(dir, 'bevy.ktx2'))));
  const [nx, ny, nz] = [3, 2, 3];
  check.check(`${name}: vkFormat R16G16B16A16_SFLOAT`, ktx.vkFormat === 97, String(ktx.vkFormat));
  check.check(`${name}: typeSize 2`, ktx.typeSize === 2);
  check.check(`${name}: size (NX, 2 NY, 3 NZ)`, ktx.pixelWidth === nx && ktx.pixelHeight === 2 * ny && ktx.pixelDepth === 3 * nz,
              `${ktx.pixelWidth} x ${ktx.pixelHeight} x ${ktx.pixelDepth}`);
  check.check(`${name}: one level, one face, no layers, no supercompression`,
              ktx.levels.length === 1 && ktx.faceCount === 1 && ktx.layerCount === 0 && ktx.supercompressionScheme === 0);
  const dfd = ktx.dataFormatDescriptor[0];
  check.check(`${name}: DFD RGBSDA linear BT.709, 4 samples of 16 bits`,
              dfd.colorModel === KHR_DF_MODEL_RGBSDA && dfd.transferFunction === KHR_DF_TRANSFER_LINEAR &&
              dfd.colorPrimaries === KHR_DF_PRIMARIES_BT709 && dfd.samples.length === 4 && dfd.samples.every((s) => s.bitLength === 15));
  const data = ktx.levels[0].levelData;
  const texel = (x, y, z) => {
    const at = 8 * (x + ktx.pixelWidth * (y + ktx.pixelHeight * z));
    return [0, 1, 2, 3].map((k) => half(data[at + 2 * k] | (data[at + 2 * k + 1] << 8)));
  };
  for (const probe of truth.probes) {
    const x = probe.index % nx, y = Math.floor(probe.index / nx) % ny, z = Math.floor(probe.index / (nx * ny));
    const scale = check.scaleOf(probe.e_over_pi);
    for (let a = 0; a < 3; a++)
      for (let s = 0; s < 2; s++) {
        const t = texel(x, y + ny * s, z + nz * a);
        check.check(`${name} probe ${probe.index}: alpha 1`, t[3] === 1);
        if (probe.valid) check.close(`${name} probe ${probe.index} axis ${a} sign ${s}`, t.slice(0, 3), probe.e_over_pi[2 * a + s], scale, 1e-3);
        else check.check(`${name} probe ${probe.index} (invalid, dilated): finite`, t.every(Number.isFinite));
      }
  }
}
check.finish();
