// Spherical harmonics for the browser, in prt's conventions (docs/conventions.md, "Spherical harmonic
// basis", "World frame and rotations", "Environment maps"): real orthonormal SH WITH the Condon-Shortley
// phase, flat index i = l(l+1)+m, evaluated on world directions (right-handed, +Y up) as fixed
// polynomials in (x, y, z) with polar axis +Z. Y_1,-1 = -0.4886 y, Y_1,0 = 0.4886 z, Y_1,1 = -0.4886 x.
// "bands" n means l = 0 .. n-1 (n^2 coefficients). Everything is computed in double (JS numbers).
//
// RGB coefficient sets are Float64Array(3 n^2), coefficient-major: [r0, g0, b0, r1, g1, b1, ...],
// as in `prt light` JSON ("coefficients": [[r, g, b], ...]).
import { DataUtils, HalfFloatType } from 'three';

export const MAX_BANDS = 16;

function checkBands(bands) {
  if (!Number.isInteger(bands) || bands < 1 || bands > MAX_BANDS) {
    throw new RangeError(`sh.js: bands ${bands} is out of range 1..${MAX_BANDS}`);
  }
}

// K_lm = sqrt((2l+1)/(4 pi) (l-|m|)!/(l+|m|)!), times sqrt(2) for m != 0; indexed [l][|m|].
const normalisationCache = new Map();
function normalisation(bands) {
  if (normalisationCache.has(bands)) return normalisationCache.get(bands);
  const table = [];
  for (let l = 0; l < bands; l++) {
    const row = [];
    for (let m = 0; m <= l; m++) {
      let ratio = 1;  // (l-m)!/(l+m)!
      for (let k = l - m + 1; k <= l + m; k++) ratio /= k;
      row.push(Math.sqrt((2 * l + 1) / (4 * Math.PI) * ratio) * (m === 0 ? 1 : Math.SQRT2));
    }
    table.push(row);
  }
  normalisationCache.set(bands, table);
  return table;
}

/// Evaluates the n^2 basis functions at direction (x, y, z) (unit length for the basis's values; a
/// non-unit vector gives the polynomials' values) into out[0 .. n^2-1]; returns out.
/// Associated Legendre functions include (-1)^m (Condon-Shortley); with P_l^m(z) = Pbar_l^m(z) sin^m
/// and C_m + i S_m = (x + i y)^m, Y_lm = K Pbar_l^|m|(z) C_|m| (m > 0), S_|m| (m < 0).
export function shEval(bands, x, y, z, out = new Float64Array(bands * bands)) {
  checkBands(bands);
  const K = normalisation(bands);
  let c = 1, s = 0;        // C_m, S_m
  let pmm = 1;             // Pbar_m^m = (-1)^m (2m-1)!!
  for (let m = 0; m < bands; m++) {
    if (m > 0) {
      const cNext = c * x - s * y;
      s = c * y + s * x;
      c = cNext;
      pmm *= -(2 * m - 1);
    }
    let p2 = 0, p1 = pmm;  // Pbar_{l-2}^m, Pbar_{l-1}^m while l runs up from m
    for (let l = m; l < bands; l++) {
      let p;
      if (l === m) p = pmm;
      else if (l === m + 1) p = z * (2 * m + 1) * pmm;
      else p = ((2 * l - 1) * z * p1 - (l + m - 1) * p2) / (l - m);
      if (l > m) { p2 = p1; p1 = p; }
      const base = l * (l + 1);
      if (m === 0) out[base] = K[l][0] * p;
      else {
        out[base + m] = K[l][m] * p * c;
        out[base - m] = K[l][m] * p * s;
      }
    }
  }
  return out;
}

/// Reads three.js equirect data as three's loaders give it (RGBELoader, EXRLoader, a DataTexture):
/// `texture.image = {data, width, height}`, 3 or 4 channels, Float32Array or (HalfFloatType) Uint16Array
/// half floats. Rows run bottom first when texture.flipY is false (EXRLoader), top first when it is
/// true (RGBELoader). Returns {width, height, row(j, out)}: row j (from the top) as linear RGB triples
/// in `out` (Float64Array(3 width)), NaN, +-Inf and negative values as 0 (as prt's loader sets them,
/// docs/conventions.md).
export function equirectRows(texture) {
  const { data, width, height } = texture.image;
  const channels = data.length / (width * height);
  if (!(channels === 3 || channels === 4) || width !== 2 * height) {
    throw new Error(`sh.js: equirect image must be 2:1 with 3 or 4 channels (got ${width}x${height}, ${channels} channels)`);
  }
  const half = texture.type === HalfFloatType || data instanceof Uint16Array;
  const bottomFirst = texture.flipY === false;
  const row = (j, out) => {
    const start = (bottomFirst ? height - 1 - j : j) * width * channels;
    for (let i = 0; i < width; i++) {
      for (let c = 0; c < 3; c++) {
        const raw = data[start + i * channels + c];
        const v = half ? DataUtils.fromHalfFloat(raw) : raw;
        out[3 * i + c] = Number.isFinite(v) && v > 0 ? v : 0;
      }
    }
    return out;
  };
  return { width, height, row };
}

/// Projects an equirect radiance map (see equirectRows) to `bands` bands, texel by texel: each texel
/// is the radiance at its centre, direction (sin t cos p, cos t, sin t sin p) with t = pi (y + 1/2) / H
/// (y from the top) and p = 2 pi ((x + 1/2) / W - 1/2), weighted by its exact solid angle
/// (cos t_top - cos t_bottom) 2 pi / W. Returns RGB coefficients (Float64Array(3 n^2)).
/// options.rgbe: the data came from three's RGBELoader, which decodes a mantissa m as m/255 2^(e-128)
/// where Radiance's rgbe2float (and prt, through OpenImageIO) read m/256 2^(e-128): the sums are
/// scaled by 255/256 to give prt's values.
export function projectEquirect(texture, bands, { rgbe = false } = {}) {
  checkBands(bands);
  const { width, height, row: readRow } = equirectRows(texture);
  const pixels = new Float64Array(3 * width);
  const n2 = bands * bands;
  const sums = new Float64Array(3 * n2);
  const row = new Float64Array(3 * n2);
  const y = new Float64Array(n2);
  for (let j = 0; j < height; j++) {
    const theta = Math.PI * (j + 0.5) / height;
    const omega = (Math.cos(Math.PI * j / height) - Math.cos(Math.PI * (j + 1) / height)) * 2 * Math.PI / width;
    row.fill(0);
    readRow(j, pixels);
    const sinTheta = Math.sin(theta), cosTheta = Math.cos(theta);
    for (let i = 0; i < width; i++) {
      const r = pixels[3 * i], g = pixels[3 * i + 1], b = pixels[3 * i + 2];
      if (r === 0 && g === 0 && b === 0) continue;
      const phi = 2 * Math.PI * ((i + 0.5) / width - 0.5);
      shEval(bands, sinTheta * Math.cos(phi), cosTheta, sinTheta * Math.sin(phi), y);
      for (let k = 0; k < n2; k++) {
        row[3 * k] += r * y[k];
        row[3 * k + 1] += g * y[k];
        row[3 * k + 2] += b * y[k];
      }
    }
    for (let k = 0; k < 3 * n2; k++) sums[k] += row[k] * omega;
  }
  if (rgbe) for (let k = 0; k < 3 * n2; k++) sums[k] *= 255 / 256;
  return sums;
}

/// R = Ry(yaw) Rx(pitch) Rz(roll), degrees, right-handed about the world axes (prt's --rotate), as a
/// row-major 3x3 array acting on column vectors (d' = R d).
export function rotationFromYawPitchRoll(yaw, pitch, roll) {
  const rad = Math.PI / 180;
  const [cy, sy] = [Math.cos(yaw * rad), Math.sin(yaw * rad)];
  const [cp, sp] = [Math.cos(pitch * rad), Math.sin(pitch * rad)];
  const [cr, sr] = [Math.cos(roll * rad), Math.sin(roll * rad)];
  const Ry = [cy, 0, sy, 0, 1, 0, -sy, 0, cy];
  const Rx = [1, 0, 0, 0, cp, -sp, 0, sp, cp];
  const Rz = [cr, -sr, 0, sr, cr, 0, 0, 0, 1];
  return multiply3(Ry, multiply3(Rx, Rz));
}

export function multiply3(a, b) {
  const out = new Array(9).fill(0);
  for (let r = 0; r < 3; r++) for (let c = 0; c < 3; c++) for (let k = 0; k < 3; k++) out[3 * r + c] += a[3 * r + k] * b[3 * k + c];
  return out;
}

// Gauss-Legendre nodes and weights on [-1, 1] (Newton iteration on P_count).
function gaussLegendre(count) {
  const nodes = [], weights = [];
  for (let i = 0; i < count; i++) {
    let x = Math.cos(Math.PI * (i + 0.75) / (count + 0.5));
    let dp = 1;
    for (let iteration = 0; iteration < 100; iteration++) {
      let p0 = 1, p1 = x;
      for (let k = 2; k <= count; k++) [p0, p1] = [p1, ((2 * k - 1) * x * p1 - (k - 1) * p0) / k];
      dp = count * (x * p1 - p0) / (x * x - 1);
      const step = p1 / dp;
      x -= step;
      if (Math.abs(step) < 1e-16) break;
    }
    nodes.push(x);
    weights.push(2 / ((1 - x * x) * dp * dp));
  }
  return { nodes, weights };
}

/// The SH rotation of an ACTIVE rotation R (row-major 3x3, column vectors, orthonormal): one
/// (2l+1)x(2l+1) block per band with sum_i c'_i Y_i(d) = sum_i c_i Y_i(R^-1 d). Built as the exact
/// integrals B_ij = integral Y_i(d) Y_j(R^T d) dd by a product quadrature exact for polynomials of degree
/// 2(n-1) (floor(n-1)+1 Gauss-Legendre nodes in z times 2n-1 uniform angles). Returns Float64Array
/// blocks, block[l][(m + l) * (2l+1) + (k + l)].
export function shRotation(bands, R) {
  checkBands(bands);
  const degree = 2 * (bands - 1);
  const { nodes, weights } = gaussLegendre(Math.floor(degree / 2) + 1);
  const phis = degree + 1;
  const blocks = [];
  for (let l = 0; l < bands; l++) blocks.push(new Float64Array((2 * l + 1) * (2 * l + 1)));
  const a = new Float64Array(bands * bands), b = new Float64Array(bands * bands);
  for (let q = 0; q < nodes.length; q++) {
    const z = nodes[q], s = Math.sqrt(Math.max(0, 1 - z * z));
    for (let p = 0; p < phis; p++) {
      const phi = 2 * Math.PI * (p + 0.5) / phis;
      const x = s * Math.cos(phi), y = s * Math.sin(phi);
      const w = weights[q] * 2 * Math.PI / phis;
      shEval(bands, x, y, z, a);
      // R^T d: column r of R dotted with d.
      shEval(bands, R[0] * x + R[3] * y + R[6] * z, R[1] * x + R[4] * y + R[7] * z, R[2] * x + R[5] * y + R[8] * z, b);
      for (let l = 0; l < bands; l++) {
        const size = 2 * l + 1, base = l * l, block = blocks[l];
        for (let i = 0; i < size; i++) for (let j = 0; j < size; j++) block[i * size + j] += w * a[base + i] * b[base + j];
      }
    }
  }
  return blocks;
}

/// Rotates RGB coefficients (coefficient-major, n^2 triples) by the blocks of shRotation; returns a new
/// Float64Array. Coefficients beyond the blocks' bands are dropped.
export function rotateRgb(coefficients, blocks) {
  const bands = blocks.length;
  const out = new Float64Array(3 * bands * bands);
  for (let l = 0; l < bands; l++) {
    const size = 2 * l + 1, base = l * l, block = blocks[l];
    for (let i = 0; i < size; i++) {
      for (let j = 0; j < size; j++) {
        const w = block[i * size + j];
        for (let c = 0; c < 3; c++) out[3 * (base + i) + c] += w * coefficients[3 * (base + j) + c];
      }
    }
  }
  return out;
}

/// The run-time band truncation of docs/conventions.md ("Run-time band truncation", prt's `--bands N`):
/// RGB coefficients (coefficient-major, n^2 triples) with every coefficient of band l >= `keep` set to 0
/// and bands 0..keep-1 kept as they are; returns a new Float64Array of the same length. keep in
/// 1..bands of the coefficients (a larger one keeps all).
export function truncateBands(coefficients, keep) {
  if (!(Number.isInteger(keep) && keep >= 1)) throw new Error(`truncateBands: ${keep} bands is not a whole number >= 1`);
  const out = Float64Array.from(coefficients);
  out.fill(0, Math.min(out.length, 3 * keep * keep));
  return out;
}

/// RGB coefficients from a `prt light` JSON object (already parsed): checks basis, index and frame
/// strings and the count; returns { bands, coefficients: Float64Array(3 n^2), discs }.
export function fromLightFile(json) {
  if (json.basis !== 'real-orthonormal-condon-shortley' || json.index !== 'l*(l+1)+m' || json.frame !== 'right-handed, +Y up') {
    throw new Error('sh.js: the lighting file is not in prt\'s SH conventions (basis, index or frame)');
  }
  const bands = json.bands;
  checkBands(bands);
  if (!Array.isArray(json.coefficients) || json.coefficients.length !== bands * bands) {
    throw new Error(`sh.js: the lighting file must hold ${bands * bands} coefficients`);
  }
  return { bands, coefficients: Float64Array.from(json.coefficients.flat()), discs: json.discs || [] };
}

/// SH radiance coefficients (Float64Array(3 n^2), coefficient-major RGB) of a disc (light/disc.h,
/// docs/conventions.md "Sun and sky"): a cap of uniform radiance L = E / (pi sin^2 a) about the unit
/// direction d (toward the light), E the irradiance at normal incidence per channel, a the angular radius
/// in radians (0 < a <= pi/4). Exact: c_lm = 2 pi L (integral_{cos a}^1 P_l) Y_lm(d), the integral taken as
/// sin^2 a P_l'(cos a) / (l (l+1)) (l >= 1) without the cancellation of (P_{l-1} - P_{l+1}) / (2l+1).
export function discCoefficients(bands, direction, irradiance, angularRadius) {
  checkBands(bands);
  const [x, y, z] = direction, norm = Math.hypot(x, y, z);
  const basis = shEval(bands, x / norm, y / norm, z / norm);
  const c = Math.cos(angularRadius), s2 = Math.sin(angularRadius) ** 2;
  const integral = [1 - c];  // l = 0
  let p0 = 1, p1 = c, dPrevious = 0, dCurrent = 1;  // P_{l-1}, P_l; P'_{l-1}, P'_l at l = 1
  for (let l = 1; l < bands; l++) {
    integral.push(s2 * dCurrent / (l * (l + 1)));
    // P'_{l+1} = P'_{l-1} + (2l+1) P_l; P_{l+1} = ((2l+1) c P_l - l P_{l-1}) / (l+1)
    [dPrevious, dCurrent] = [dCurrent, dPrevious + (2 * l + 1) * p1];
    [p0, p1] = [p1, ((2 * l + 1) * c * p1 - l * p0) / (l + 1)];
  }
  const out = new Float64Array(3 * bands * bands);
  for (let l = 0; l < bands; l++) {
    for (let i = l * l; i < (l + 1) * (l + 1); i++) {
      for (let ch = 0; ch < 3; ch++) out[3 * i + ch] = 2 * Math.PI * irradiance[ch] / (Math.PI * s2) * integral[l] * basis[i];
    }
  }
  return out;
}
