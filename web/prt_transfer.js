// prt's engine-ready glTF in three.js: a GLTFLoader plugin for the PRT_transfer extension
// (docs/formats.md, "The engine glTF") and the materials and per-frame work that relight it, as
// `prt render` does (src/render/pass_cpca.cpp, shaders/prt_cpca.*, shaders/prt_sun.frag):
//
//   const loader = new GLTFLoader().register((parser) => new PrtTransferPlugin(parser));
//   const gltf = await loader.loadAsync('baked.glb');
//   const prt = new PrtRelighting(gltf);          // PRT materials on every primitive with transfer
//   scene.add(gltf.scene);
//   prt.setLighting(lighting);                     // {bands, coefficients (RGB SH, world frame), discs}
//   prt.setRotation(R);                            // environment rotation (3x3 row-major, active)
//   prt.update(renderer);                          // per frame, before renderer.render(scene, camera)
//
// Per frame on the CPU (one dot product per cluster, term and channel: K (N+1) C B^2 multiply-adds):
// s_kj[c] = sum_i T_kj[c][i] L_c[i] + sum_i Tb_kj[c][i] D_c[i] with the rotated sky L and the discs'
// SH D (bounce models only); in the vertex shader a vertex of cluster k with weights w gets
// s_k0 + sum_j w_j s_kj (per texel: a GPU pass does so for every texel and builds prt's mip chain of the
// result, web/prt_lightmap_mips.js, which the lightmap material samples trilinearly). Textured scenes:
// the vertex radiance is divided by _PRT_ALBEDO per channel (0 where it is 0) and the pixel multiplies
// by its base colour (factor x texture x COLOR_0); the discs add (albedo / pi) E max(n.d, 0) V per pixel,
// V from an orthographic depth map per disc filtered PCSS-style for the disc's size (web/prt_sun.js);
// with discs every channel is clamped at 0.
import { DataTexture, FloatType, NearestFilter, RGBAFormat } from 'three';
import { discCoefficients, rotateRgb, shRotation, truncateBands } from './sh.js';
import { createPrtMaterial } from './prt_material.js';
import { PrtSun } from './prt_sun.js';
import { createLightmapMaterial, loadLightmap } from './prt_lightmap.js';
import { LightmapRadiance } from './prt_lightmap_mips.js';

const EXTENSION = 'PRT_transfer';

export const MAX_VERTEX_ATTRIBUTES = 16;  // WebGL2's MAX_VERTEX_ATTRIBS minimum (and Chromium's value)

/// GLTFLoader plugin: reads the root PRT_transfer models (their means and bases accessors) into
/// gltf.userData.prtTransfer = {version, models: [{kind, bands, channels, clusters, terms, bounce,
/// means: Float32Array, bases: Float32Array}]}, and marks each mesh whose primitive carries the extension
/// with mesh.userData.prtTransfer = {model} (per vertex) or mesh.userData.prtLightmap = {model, texCoord,
/// width, height, layers, cluster, weights} (per texel: "width" in the extension; web/prt_lightmap.js).
/// Throws on a malformed extension (one line naming it).
export class PrtTransferPlugin {
  constructor(parser) {
    this.parser = parser;
    this.name = EXTENSION;
  }

  async afterRoot(result) {
    const json = this.parser.json;
    const root = json.extensions && json.extensions[EXTENSION];
    if (!root) return;
    if (root.version !== 1 || !Array.isArray(root.models)) throw new Error(`${EXTENSION}: version ${root.version} is not 1, or no models`);
    const models = await Promise.all(root.models.map((m, i) => this.loadModel(m, i)));
    result.userData.prtTransfer = { version: 1, models };
    const lightmaps = [];
    result.scene.traverse((object) => {
      if (!object.isMesh) return;
      const where = this.parser.associations.get(object);
      if (!where || where.meshes === undefined || where.primitives === undefined) return;
      const primitive = json.meshes[where.meshes].primitives[where.primitives];
      const ext = primitive.extensions && primitive.extensions[EXTENSION];
      if (!ext) return;
      if (!(ext.model >= 0 && ext.model < models.length)) throw new Error(`${EXTENSION}: mesh ${where.meshes} names model ${ext.model} of ${models.length}`);
      if (ext.width !== undefined) {
        lightmaps.push(loadLightmap(this.parser, ext, models[ext.model], `${EXTENSION} of mesh ${where.meshes}`).then((lm) => { object.userData.prtLightmap = lm; }));
        return;
      }
      const count = Object.keys(object.geometry.attributes).length;
      if (count > MAX_VERTEX_ATTRIBUTES) throw new Error(`${EXTENSION}: mesh ${where.meshes} has ${count} vertex attributes (WebGL2 allows ${MAX_VERTEX_ATTRIBUTES})`);
      const clusters = object.geometry.attributes._prt_cluster;
      const k = models[ext.model].clusters;
      for (let i = 0; clusters && i < clusters.count; i++) {
        const c = clusters.getX(i);
        if (!(Number.isInteger(c) && c >= 0 && c < k)) throw new Error(`${EXTENSION}: mesh ${where.meshes} vertex ${i} has cluster ${c}, outside 0..${k - 1}`);
      }
      object.userData.prtTransfer = { model: ext.model };
    });
    await Promise.all(lightmaps);
  }

  async loadModel(m, index) {
    const d = m.channels * m.bands * m.bands * (m.bounce ? 2 : 1);
    const what = `${EXTENSION} model ${index}`;
    if (!(m.channels === 1 || m.channels === 3) || !(m.bands >= 1 && m.bands <= 16) || !(m.clusters >= 1) || !(m.terms >= 0)) {
      throw new Error(`${what}: channels ${m.channels}, bands ${m.bands}, clusters ${m.clusters} or terms ${m.terms} out of range`);
    }
    const [means, bases] = await Promise.all([m.means, m.bases].map((a) => this.parser.getDependency('accessor', a)));
    if (means.array.length !== m.clusters * d || bases.array.length !== m.clusters * m.terms * d) {
      throw new Error(`${what}: means hold ${means.array.length} values, bases ${bases.array.length}; expected ${m.clusters * d} and ${m.clusters * m.terms * d}`);
    }
    return { kind: m.kind, bands: m.bands, channels: m.channels, clusters: m.clusters, terms: m.terms, bounce: !!m.bounce,
             means: Float32Array.from(means.array), bases: Float32Array.from(bases.array), pointSize: d };
  }
}

// The per-cluster shaded values of one model: an RGBA32F texture of K (N+1) texels (row-major over a
// width of at most 1024), texel k (N+1) + j = s_kj.
function productsTexture(model) {
  const count = model.clusters * (model.terms + 1);
  const width = Math.min(count, 1024), height = Math.ceil(count / width);
  const texture = new DataTexture(new Float32Array(4 * width * height), width, height, RGBAFormat, FloatType);
  texture.minFilter = texture.magFilter = NearestFilter;
  texture.generateMipmaps = false;
  texture.needsUpdate = true;
  return texture;
}

/// s_kj for every cluster k and term j into `out` (RGBA per texel): sky L and discs D are RGB SH
/// (coefficient-major) with at least the model's bands; D may be null (no bounce light).
export function clusterProducts(model, sky, discs, out) {
  const n2 = model.bands * model.bands, d = model.pointSize, terms = model.terms;
  const shade = (values, offset, channel, light) => {
    let sum = 0;
    for (let i = 0; i < n2; i++) sum += values[offset + i] * light[3 * i + channel];
    return sum;
  };
  for (let k = 0; k < model.clusters; k++) {
    for (let j = 0; j <= terms; j++) {
      const values = j === 0 ? model.means : model.bases;
      const base = j === 0 ? k * d : (k * terms + j - 1) * d;
      const texel = 4 * (k * (terms + 1) + j);
      for (let c = 0; c < 3; c++) {
        const section = model.channels === 1 ? 0 : c * n2;
        let s = shade(values, base + section, c, sky);
        if (discs && model.bounce) s += shade(values, base + model.channels * n2 + section, c, discs);
        out[texel + c] = s;
      }
      out[texel + 3] = 1;
    }
  }
}

/// The relighting of one loaded glTF (with PrtTransferPlugin): replaces the material of every mesh with
/// transfer by a PRT material that keeps its base colour (factor, texture, vertex colours).
/// options.textured: apply the albedo split (docs/conventions.md "Albedo and textures"); default: when
/// any baked mesh's material has a base colour texture (what `prt render` calls a textured mesh).
/// options.shadowMapSize: the discs' depth maps' texels per side (default 2048, prt render's).
export class PrtRelighting {
  constructor(gltf, options = {}) {
    const info = gltf.userData.prtTransfer;
    if (!info) throw new Error('PrtRelighting: the glTF has no PRT_transfer extension (load it with PrtTransferPlugin)');
    this.models = info.models.map((model) => ({ ...model, products: productsTexture(model) }));
    this.meshes = [];
    gltf.scene.traverse((o) => { if (o.isMesh && (o.userData.prtTransfer || o.userData.prtLightmap)) this.meshes.push(o); });
    const textured = options.textured ?? this.meshes.some((m) => m.userData.prtTransfer && !!m.material.map);
    this.sun = new PrtSun(gltf.scene, this.meshes, { mapSize: options.shadowMapSize });
    this.lightmaps = [];  // LightmapRadiance of each per-texel mesh
    for (const mesh of this.meshes) {
      if (mesh.userData.prtLightmap) {
        const lightmap = mesh.userData.prtLightmap, model = this.models[lightmap.model];
        const radiance = new LightmapRadiance(lightmap, model);
        this.lightmaps.push(radiance);
        mesh.material = createLightmapMaterial(mesh, lightmap, model, radiance, this.sun);
        continue;
      }
      const model = this.models[mesh.userData.prtTransfer.model];
      mesh.material = createPrtMaterial(mesh, model, { textured, sun: this.sun });
    }
    this.bands = Math.max(...this.models.map((m) => m.bands));
    this.shadingBands = 0;  // 0: all
    this.rotation = [1, 0, 0, 0, 1, 0, 0, 0, 1];
    this.lighting = null;
    this.sunEnabled = true;
    this.dirty = true;
  }

  /// Lighting in the world frame before rotation: {bands, coefficients: RGB SH (coefficient-major, at
  /// least as many bands as the transfer), discs: [{direction, irradiance, angular_radius_degrees}]}
  /// (a `prt light` JSON through sh.js fromLightFile, or projectEquirect of an environment map).
  setLighting(lighting) {
    const needed = this.bands;
    if (lighting.bands < needed) throw new Error(`PrtRelighting: the lighting has ${lighting.bands} bands, the transfer ${needed}`);
    this.lighting = lighting;
    this.dirty = true;
  }

  /// The environment's active rotation (row-major 3x3 acting on column vectors, prt's --rotate).
  setRotation(R) {
    if (R.every((v, i) => v === this.rotation[i])) return;
    this.rotation = Array.from(R);
    this.dirty = true;
  }

  /// Shades with the lighting truncated to its first `bands` whole bands (prt render's --bands N: a cheaper
  /// tier of the same bake, sh.js truncateBands); 0: all of the transfer's bands.
  setBands(bands) {
    if (!(Number.isInteger(bands) && bands >= 0 && bands <= this.bands))
      throw new Error(`PrtRelighting: ${bands} bands is out of range 0..${this.bands}`);
    if (bands === this.shadingBands) return;
    this.shadingBands = bands;
    this.dirty = true;
  }

  /// Turns the discs' direct and bounce light on or off.
  setSunEnabled(enabled) {
    if (this.sunEnabled === !!enabled) return;
    this.sunEnabled = !!enabled;
    this.dirty = true;
  }

  /// Recomputes the products (and the discs' shadow maps) when the lighting, rotation or sun changed.
  update(renderer) {
    if (!this.dirty || !this.lighting) return;
    const bands = this.bands;
    const blocks = shRotation(bands, this.rotation);
    const keep = this.shadingBands || bands;
    const sky = truncateBands(rotateRgb(this.lighting.coefficients, blocks), keep);
    const discs = this.sunEnabled ? (this.lighting.discs || []).map((disc) => rotateDisc(disc, this.rotation)) : [];
    const discSh = discs.length ? truncateBands(discs.map((d) => discCoefficients(bands, d.direction, d.irradiance, d.radius))
      .reduce((sum, c) => sum.map((v, i) => v + c[i])), keep) : null;
    for (const model of this.models) {
      clusterProducts(model, sky, discSh, model.products.image.data);
      model.products.needsUpdate = true;
    }
    for (const lightmap of this.lightmaps) lightmap.update(renderer);
    this.sun.setDiscs(discs);
    this.sun.update(renderer);
    this.dirty = false;
  }
}

// A lighting file's disc turned by R: {direction (unit), irradiance [r, g, b], radius (radians)}.
function rotateDisc(disc, R) {
  const [x, y, z] = disc.direction, n = Math.hypot(x, y, z);
  const d = [0, 1, 2].map((r) => (R[3 * r] * x + R[3 * r + 1] * y + R[3 * r + 2] * z) / n);
  return { direction: d, irradiance: disc.irradiance, radius: disc.angular_radius_degrees * Math.PI / 180 };
}
