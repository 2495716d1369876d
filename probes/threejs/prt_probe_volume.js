// prt probe volume for three.js: each attached mesh is lit by the SH of ITS OWN position, blended
// trilinearly from the probes of a `prt probes --format threejs` export and updated every frame as the
// mesh moves. No LightProbe is added to the scene (three.js adds every LightProbe to every object).
//
//   import { PrtProbeVolume } from './prt_probe_volume.js';
//   const volume = await PrtProbeVolume.load('probes.json');
//   volume.attach(mesh);           // mesh.material becomes the mesh's own copy, lit by the volume
//   volume.sample(position, sh3);  // the blended SphericalHarmonics3 at a world position
//
// Blending (documented in README.md): for a grid, the position's cell coordinates
// u = (p - lo) / ((hi - lo) / counts) - 0.5 are clamped to [0, counts - 1] per axis (outside the
// probes' span the nearest face of the grid holds), and the 8 corner probes get trilinear weights;
// invalid probes (inside geometry) get weight 0 and the rest are renormalised. If every corner with a
// non-zero weight is invalid, or the export is a point list, the nearest valid probe is used alone.
// The coefficients are three.js's (no Condon-Shortley phase, radiance): getIrradianceAt(n) gives E(n),
// and three.js's Lambert and standard materials show albedo * E(n) / pi.
import { SphericalHarmonics3, Vector3 } from 'three';

const FORMAT = 'prt-probe-volume-threejs';

export class PrtProbeVolume {
  /** @param {object} json the parsed export; throws Error naming the first problem found. */
  constructor(json) {
    if (!json || json.format !== FORMAT) throw new Error(`not a ${FORMAT} file (format: ${json && json.format})`);
    if (json.version !== 2) throw new Error(`unsupported ${FORMAT} version ${json.version} (expected 2)`);
    const n = json.count;
    if (!Number.isInteger(n) || n < 1) throw new Error(`bad probe count ${n}`);
    for (const [key, per] of [['positions', 3], ['valid', 1], ['sh', 27]])
      if (!Array.isArray(json[key]) || json[key].length !== per * n) throw new Error(`"${key}" must hold ${per * n} numbers`);
    this.count = n;
    this.layout = json.layout;
    this.positions = Float64Array.from(json.positions);
    this.valid = Uint8Array.from(json.valid);
    this.sh = Float64Array.from(json.sh);
    if (!this.valid.some((v) => v === 1)) throw new Error('the volume has no valid probe');
    if (this.layout.type === 'grid') {
      const [nx, ny, nz] = this.layout.counts;
      if (nx * ny * nz !== n) throw new Error(`grid ${nx}x${ny}x${nz} does not hold ${n} probes`);
    }
  }

  /** Fetches and parses an export. */
  static async load(url) {
    const response = await fetch(url);
    if (!response.ok) throw new Error(`${url}: HTTP ${response.status}`);
    return new PrtProbeVolume(await response.json());
  }

  /** The valid probe nearest to `position` (a Vector3). */
  nearestValid(position) {
    let best = -1, bestDistance = Infinity;
    for (let i = 0; i < this.count; i++) {
      if (!this.valid[i]) continue;
      const dx = this.positions[3 * i] - position.x, dy = this.positions[3 * i + 1] - position.y, dz = this.positions[3 * i + 2] - position.z;
      const d = dx * dx + dy * dy + dz * dz;
      if (d < bestDistance) { bestDistance = d; best = i; }
    }
    return best;
  }

  /** [[probe index, weight], ...] with weights summing to 1 (see the blending rule above). */
  weightsAt(position) {
    if (this.layout.type !== 'grid') return [[this.nearestValid(position), 1]];
    const counts = this.layout.counts, [lo, hi] = this.layout.bounds, p = [position.x, position.y, position.z];
    const base = [0, 0, 0], frac = [0, 0, 0];
    for (let a = 0; a < 3; a++) {
      const u = Math.min(Math.max((p[a] - lo[a]) / ((hi[a] - lo[a]) / counts[a]) - 0.5, 0), counts[a] - 1);
      base[a] = Math.min(Math.floor(u), Math.max(counts[a] - 2, 0));
      frac[a] = counts[a] > 1 ? u - base[a] : 0;
    }
    const weights = [];
    let total = 0;
    for (let corner = 0; corner < 8; corner++) {
      let w = 1, index = 0, stride = 1, inside = true;
      for (let a = 0; a < 3; a++) {
        const step = (corner >> a) & 1;
        if (step && counts[a] === 1) { inside = false; break; }
        w *= step ? frac[a] : 1 - frac[a];
        index += (base[a] + step) * stride;
        stride *= counts[a];
      }
      if (!inside || w === 0 || !this.valid[index]) continue;
      weights.push([index, w]);
      total += w;
    }
    if (total === 0) return [[this.nearestValid(position), 1]];
    return weights.map(([i, w]) => [i, w / total]);
  }

  /** The blended SH at a world position, written into `target` (a new SphericalHarmonics3 if omitted). */
  sample(position, target = new SphericalHarmonics3()) {
    for (const c of target.coefficients) c.set(0, 0, 0);
    for (const [i, w] of this.weightsAt(position))
      for (let k = 0; k < 9; k++) {
        const at = 27 * i + 3 * k;
        target.coefficients[k].x += w * this.sh[at];
        target.coefficients[k].y += w * this.sh[at + 1];
        target.coefficients[k].z += w * this.sh[at + 2];
      }
    return target;
  }

  /**
   * Lights `mesh` with the volume: gives it its own copy of its material (MeshLambertMaterial,
   * MeshStandardMaterial, MeshPhysicalMaterial, MeshPhongMaterial: any material with three.js's
   * indirect-diffuse term) whose shader adds getLightProbeIrradiance of the blended SH at the mesh's
   * world position, re-sampled before every draw. Returns a function that detaches it again.
   */
  attach(mesh) {
    const original = mesh.material;
    const material = original.clone();
    const sh = new SphericalHarmonics3();
    const uniform = { value: sh.coefficients };
    material.onBeforeCompile = (shader) => {
      shader.uniforms.prtProbeSH = uniform;
      shader.fragmentShader = shader.fragmentShader
        .replace('#include <lights_pars_begin>', '#include <lights_pars_begin>\nuniform vec3 prtProbeSH[ 9 ];')
        .replace('#include <lights_fragment_begin>',
          '#include <lights_fragment_begin>\n#if defined( RE_IndirectDiffuse )\n\tirradiance += getLightProbeIrradiance( prtProbeSH, geometryNormal );\n#endif');
    };
    material.customProgramCacheKey = () => 'prt-probe-volume';
    const where = new Vector3();
    const previous = mesh.onBeforeRender;
    mesh.onBeforeRender = (...args) => {
      this.sample(mesh.getWorldPosition(where), sh);
      material.uniformsNeedUpdate = true;
      previous.apply(mesh, args);
    };
    mesh.material = material;
    return () => {
      mesh.material = original;
      mesh.onBeforeRender = previous;
      material.dispose();
    };
  }
}
