// Shared helpers of the engine tests: arguments, running prt, the test scene, PNG decoding, the
// fixture's truth file and the comparison every test makes.
import { spawnSync } from 'node:child_process';
import { readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { inflateSync } from 'node:zlib';

/** The value after --name on the command line (or the fallback; exits 1 if neither). */
export function argument(name, fallback) {
  const i = process.argv.indexOf(`--${name}`);
  if (i >= 0 && i + 1 < process.argv.length) return process.argv[i + 1];
  if (fallback !== undefined) return fallback;
  console.error(`missing --${name}`);
  process.exit(1);
}

/** Runs a command; exits 1 with its output if it fails. Returns stdout. */
export function run(command, args) {
  const r = spawnSync(command, args, { encoding: 'utf8' });
  if (r.status !== 0) {
    console.error(`${command} ${args.join(' ')} failed (${r.status}):\n${r.stdout}${r.stderr}`);
    process.exit(1);
  }
  return r.stdout;
}

/** A floor [-2,2]^2 at y = 0 with an open box [-0.5,0.5] x [0,1] x [-0.5,0.5] on it (+X, top, +Z faces). */
export function writeScene(path) {
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

/** Decodes an 8-bit, non-interlaced RGB or RGBA PNG to RGBA bytes, rows from the top, values as stored. */
export function decodePng(buffer) {
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

/** The fixture folders (one per environment) the fixture test wrote under `work`. */
export function fixtureFolders(work) {
  const list = JSON.parse(readFileSync(join(work, 'fixtures.json'), 'utf8'));
  return list.map((name) => ({ name, dir: join(work, name), truth: JSON.parse(readFileSync(join(work, name, 'truth.json'), 'utf8')) }));
}

/**
 * Collects |engine - prt| <= tolerance * scale checks, scale = the largest |E/pi| component of the
 * probe over the test directions (so the tolerance is relative to the probe's brightness).
 */
export class Checker {
  constructor(name) { this.name = name; this.count = 0; this.failures = []; this.worst = 0; }
  scaleOf(values) { return Math.max(1e-12, ...values.flat().map(Math.abs)); }
  close(what, got, want, scale, tolerance) {
    this.count++;
    let error = 0;
    for (let k = 0; k < want.length; k++) error = Math.max(error, Math.abs(got[k] - want[k]) / scale);
    this.worst = Math.max(this.worst, error);
    if (!(error <= tolerance)) this.failures.push(`${what}: engine ${fmt(got)}, prt ${fmt(want)} (relative error ${error.toExponential(2)} > ${tolerance})`);
  }
  check(what, ok, detail = '') {
    this.count++;
    if (!ok) this.failures.push(`${what}${detail ? ': ' + detail : ''}`);
  }
  /** Prints the summary and exits 0 (pass) or 1. */
  finish() {
    for (const f of this.failures.slice(0, Number(process.env.PRT_SHOW_FAILURES || 20))) console.log(`FAIL ${f}`);
    if (this.failures.length > 20) console.log(`... and ${this.failures.length - 20} more failures`);
    console.log(`${this.name}: ${this.count - this.failures.length} passed, ${this.failures.length} failed (worst relative error ${this.worst.toExponential(2)})`);
    process.exit(this.failures.length ? 1 : 0);
  }
}

export function fmt(v) { return `(${Array.from(v).map((x) => Number(x).toPrecision(6)).join(', ')})`; }

/**
 * Compiles one GLSL function of an engine's shader source to JavaScript, evaluated once per colour
 * channel c: every vec3 becomes that channel's scalar, so the straight-line arithmetic of the SH
 * irradiance functions runs unchanged. `direction` names the vec3 parameter read by components
 * (normal.x -> normal[0]); `vectors` names the other vec3 inputs (parameters or uniforms; an input
 * used as `name[ i ]` is an array of vec3). Returns f(direction, inputs) -> [r, g, b], inputs mapping
 * each vector name to [r,g,b] (or an array of them). Anything outside that subset (calls, branches,
 * textures, vec constructors) throws, so a changed shader fails the test instead of being misread.
 */
export function glslFunction(source, name, direction, vectors) {
  const start = source.search(new RegExp(`\\bvec3\\s+${name}\\s*\\(`));
  if (start < 0) throw new Error(`no function ${name} in the shader source`);
  const open = source.indexOf('{', start);
  let depth = 0, end = open;
  for (; end < source.length; end++) {
    if (source[end] === '{') depth++;
    if (source[end] === '}' && --depth === 0) break;
  }
  let js = source.slice(open + 1, end).replace(/\/\/[^\n]*/g, '');
  js = js.replace(/\b(vec3|float)\s+/g, 'let ').replace(/\.rgb\b/g, '');
  js = js.replace(new RegExp(`\\b${direction}\\.([xyz])\\b`, 'g'), (m, a) => `${direction}[${'xyz'.indexOf(a)}]`);
  for (const v of vectors) {
    js = js.replace(new RegExp(`\\b${v}\\s*\\[\\s*(\\d+)\\s*\\]`, 'g'), `I.${v}[$1][c]`);
    js = js.replace(new RegExp(`(?<![.\\w])${v}\\b(?!\\s*\\[)`, 'g'), `I.${v}[c]`);
  }
  const leftover = js.replace(/I\.\w+(\[\d+\])?\[c\]/g, '').replace(new RegExp(`\\b${direction}\\[\\d\\]`, 'g'), '');
  if (/\b(vec[234]|mat[234]|for|while|if|texture\w*|pow|max|min|dot|normalize)\b|[?:]/.test(leftover) || /\w+\s*\(/.test(leftover))
    throw new Error(`${name}: GLSL outside the translated subset: ${js}`);
  const channel = new Function(direction, 'I', 'c', js);
  return (d, inputs) => [0, 1, 2].map((c) => channel(d, inputs, c));
}

/** GLB: rewrites the JSON chunk of the file at `path` with `edit(json)`, keeping the BIN chunk. */
export function editGlb(path, edit) {
  const glb = readFileSync(path);
  const jsonLength = glb.readUInt32LE(12);
  const json = JSON.parse(glb.toString('utf8', 20, 20 + jsonLength));
  const bin = glb.subarray(20 + jsonLength);
  edit(json);
  let text = JSON.stringify(json);
  while (text.length % 4) text += ' ';
  const header = Buffer.alloc(20);
  header.write('glTF', 0);
  header.writeUInt32LE(2, 4);
  header.writeUInt32LE(20 + text.length + bin.length, 8);
  header.writeUInt32LE(text.length, 12);
  header.writeUInt32LE(0x4e4f534a, 16);
  writeFileSync(path, Buffer.concat([header, Buffer.from(text), bin]));
}
