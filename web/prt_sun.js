// The discs (suns) of prt's split lighting in three.js: one orthographic depth map per disc (at most 4,
// the layers of one array texture), fitted as `prt render` fits it (src/render/sun_light.cpp: looking
// along -d, its square fitted to the baked meshes' world bounds across d, its depth range to their extent
// along d, depth 0 nearest the light, both sides of every triangle occluding), filtered for the disc's
// size by prt's own PCSS filter: shaders/sun_pcss.glsl, the GLSL that prt's GL renderer includes,
// loaded from the repository beside web/ (docs/conventions.md, "Sun shadow maps").
import { Box3, Color, DoubleSide, FloatType, Matrix4, NearestFilter, OrthographicCamera, RedFormat, ShaderMaterial, Vector3,
         WebGLArrayRenderTarget } from 'three';

export const MAX_DISCS = 4;
export const SHADOW_MAP_SIZE = 2048;  // texels per side, as prt render's maps (src/render/sun_light.cpp)
const FILTER_COUNT = 12;  // the PCSS filter's samples, as Renderer::bind_sun sets them (src/render/sun_light.cpp)
const SHADOW_LAYER = 31;  // the baked meshes' layer: what the depth maps see

/// shaders/sun_pcss.glsl, read relative to this module when it is imported (serve the repository's
/// shaders/ folder beside web/; in node, as the tests import the runtime, from the file system). The
/// import fails naming the file when it cannot be read.
export const PCSS_URL = new URL('../shaders/sun_pcss.glsl', import.meta.url);
const PCSS_GLSL = await readText(PCSS_URL);

async function readText(url) {
  if (url.protocol === 'file:') {
    const fs = 'node:fs/promises';  // a variable: bundlers for the browser leave it alone
    return (await import(fs)).readFile(url, 'utf8');
  }
  const response = await fetch(url).catch((e) => { throw new Error(`prt_sun: ${url}: ${e.message}`); });
  if (!response.ok) throw new Error(`prt_sun: ${url}: HTTP ${response.status}`);
  return response.text();
}

/// GLSL (ES 3.00) of the discs' uniforms (the names of shaders/sun_light.glsl), disc_visibility(k, p, n)
/// (the fraction of disc k visible from world point p with unit normal n, 0 below the horizon: sun_pcss.glsl
/// without its tile early-outs, which WebGL's lack of compute shaders leaves without their min/max tiles;
/// they are exact, so the visibility is the same) and prt_disc_light(p, n).
export const SUN_GLSL = /* glsl */ `
precision highp sampler2DArray;
#define SUN_TILE_EARLY_OUTS 0
const int max_discs = ${MAX_DISCS};
uniform int disc_count;
uniform vec3 disc_direction[max_discs];
uniform vec3 disc_irradiance[max_discs];
uniform float disc_tan_radius[max_discs];
uniform mat4 shadow_matrix[max_discs];
uniform float shadow_depth_scale[max_discs];
uniform float shadow_texel[max_discs];
uniform bool disc_shadows;
uniform int filter_count;
uniform sampler2DArray shadow_maps;

// The stored depth of map k at uv (nearest texel), 1 outside the map: WebGL has no border colour.
float map_depth(int k, vec2 uv) {
  if (any(lessThan(uv, vec2(0.0))) || any(greaterThanEqual(uv, vec2(1.0)))) return 1.0;
  return textureLod(shadow_maps, vec3(uv, float(k)), 0.0).r;
}
${PCSS_GLSL}
// sum over the discs of E_k max(n.d_k, 0) V_k (the direct light before albedo / pi).
vec3 prt_disc_light(vec3 p, vec3 n) {
  vec3 sum = vec3(0.0);
  for (int k = 0; k < max_discs; ++k) {
    if (k >= disc_count) break;
    float cos_theta = dot(n, disc_direction[k]);
    if (cos_theta <= 0.0) continue;
    sum += disc_irradiance[k] * (cos_theta * disc_visibility(k, p, n));
  }
  return sum;
}
`;

/// Vertex-stage GLSL shared by the PRT materials: prt_world_position and prt_world_normal (the normal
/// by the inverse transpose of the model matrix) for the discs' direct light, and the clip position.
export const SURFACE_VERTEX_GLSL = /* glsl */ `
out vec3 prt_world_position;
out vec3 prt_world_normal;
vec4 prt_surface() {
  vec4 world = modelMatrix * vec4(position, 1.0);
  prt_world_position = world.xyz;
  prt_world_normal = transpose(inverse(mat3(modelMatrix))) * normal;
  return projectionMatrix * viewMatrix * world;
}
`;

// A unit vector perpendicular to unit n (Duff et al. 2017's first axis, as sun_light.cpp).
function perpendicular(n) {
  const sign = n.z >= 0 ? 1 : -1;  // copysign(1, z)
  const a = -1 / (sign + n.z);
  return new Vector3(1 + sign * n.x * n.x * a, sign * n.x * n.y * a, -sign * n.x).normalize();
}

/// The discs' uniforms (shared by every PRT material) and depth maps of mapSize^2 texels (default
/// SHADOW_MAP_SIZE, prt render's; a smaller map draws faster and blurs the penumbrae's clamped radii less
/// finely than prt render does).
export class PrtSun {
  constructor(scene, meshes, { mapSize = SHADOW_MAP_SIZE } = {}) {
    if (!(Number.isInteger(mapSize) && mapSize >= 16 && mapSize <= 8192)) throw new Error(`prt_sun: shadow map size ${mapSize} is not an integer in 16..8192`);
    this.mapSize = mapSize;
    this.scene = scene;
    this.meshes = meshes;
    for (const mesh of meshes) mesh.layers.enable(SHADOW_LAYER);
    this.maps = null;  // a WebGLArrayRenderTarget of one R32F layer per disc (the window depth) and a depth buffer
    this.camera = new OrthographicCamera();
    this.camera.matrixAutoUpdate = false;
    this.camera.layers.set(SHADOW_LAYER);
    this.depthMaterial = new ShaderMaterial({
      vertexShader: 'void main() { gl_Position = projectionMatrix * modelViewMatrix * vec4(position, 1.0); }',
      fragmentShader: 'void main() { gl_FragColor = vec4(gl_FragCoord.z, 0.0, 0.0, 1.0); }',
      side: DoubleSide,
    });
    this.uniforms = {
      disc_count: { value: 0 },
      disc_direction: { value: Array.from({ length: MAX_DISCS }, () => new Vector3()) },
      disc_irradiance: { value: Array.from({ length: MAX_DISCS }, () => new Vector3()) },
      disc_tan_radius: { value: new Array(MAX_DISCS).fill(0) },
      shadow_matrix: { value: Array.from({ length: MAX_DISCS }, () => new Matrix4()) },
      shadow_depth_scale: { value: new Array(MAX_DISCS).fill(1) },
      shadow_texel: { value: new Array(MAX_DISCS).fill(1) },
      filter_count: { value: FILTER_COUNT },
      shadow_maps: { value: this.target(1).texture },
    };
    this.discs = [];
  }

  /// Discs in the world frame: [{direction (unit), irradiance [r, g, b], radius (radians)}], at most 4.
  setDiscs(discs) {
    if (discs.length > MAX_DISCS) throw new Error(`prt_sun: ${discs.length} discs; at most ${MAX_DISCS}`);
    this.discs = discs;
    const u = this.uniforms;
    u.disc_count.value = discs.length;
    discs.forEach((d, k) => {
      u.disc_direction.value[k].fromArray(d.direction).normalize();
      u.disc_irradiance.value[k].fromArray(d.irradiance);
      u.disc_tan_radius.value[k] = Math.tan(d.radius);
    });
  }

  // The depth maps' target with at least `layers` layers.
  target(layers) {
    if (!this.maps || this.maps.depth < layers) {
      if (this.maps) this.maps.dispose();
      this.maps = new WebGLArrayRenderTarget(this.mapSize, this.mapSize, layers, { depthBuffer: true });
      Object.assign(this.maps.texture, { format: RedFormat, type: FloatType, minFilter: NearestFilter, magFilter: NearestFilter, generateMipmaps: false });
      if (this.uniforms) this.uniforms.shadow_maps.value = this.maps.texture;
    }
    return this.maps;
  }

  /// Fits and draws each disc's depth map (call when the discs or the meshes' placement changed).
  update(renderer) {
    if (!this.discs.length) return;
    const bounds = new Box3();
    for (const mesh of this.meshes) { mesh.updateWorldMatrix(true, false); bounds.expandByObject(mesh, true); }
    // The depth pass draws the baked meshes alone (the shadow camera's layer) with a depth-only material
    // (both sides; it samples no map, so no map is read while it is drawn into).
    const previous = renderer.getRenderTarget();
    const materials = this.meshes.map((mesh) => mesh.material);
    for (const mesh of this.meshes) mesh.material = this.depthMaterial;
    const target = this.target(this.discs.length);
    const clear = renderer.getClearColor(new Color()), alpha = renderer.getClearAlpha();
    renderer.setClearColor(0xffffff, 1);  // depth 1 (nothing in the way) where no mesh is
    this.discs.forEach((disc, k) => {
      const fit = fitMap(bounds, new Vector3().fromArray(disc.direction).normalize(), this.mapSize);
      this.camera.projectionMatrix.copy(fit.projection);
      this.camera.projectionMatrixInverse.copy(fit.projection).invert();
      this.uniforms.shadow_matrix.value[k].copy(fit.shadowMatrix);
      this.uniforms.shadow_texel.value[k] = fit.texel;
      this.uniforms.shadow_depth_scale.value[k] = fit.depthRange;
      renderer.setRenderTarget(target, k);
      renderer.clear(true, true, false);
      renderer.render(this.scene, this.camera);
    });
    renderer.setClearColor(clear, alpha);
    this.meshes.forEach((mesh, i) => { mesh.material = materials[i]; });
    renderer.setRenderTarget(previous);
  }
}

// The orthographic view of sun_light.cpp's draw_maps for unit direction d over `bounds`, size^2 texels.
function fitMap(bounds, d, size) {
  const u = perpendicular(d), v = new Vector3().crossVectors(d, u);
  const { min: lo, max: hi } = bounds;
  const margin = 1e-3 * Math.max(1e-12, new Vector3().subVectors(hi, lo).length());
  const minC = [Infinity, Infinity, Infinity], maxC = [-Infinity, -Infinity, -Infinity];
  for (let corner = 0; corner < 8; corner++) {
    const p = new Vector3(corner & 1 ? hi.x : lo.x, corner & 2 ? hi.y : lo.y, corner & 4 ? hi.z : lo.z);
    [p.dot(u), p.dot(v), p.dot(d)].forEach((c, i) => { minC[i] = Math.min(minC[i], c); maxC[i] = Math.max(maxC[i], c); });
  }
  const half = 0.5 * Math.max(maxC[0] - minC[0], maxC[1] - minC[1]) + margin;
  const cu = 0.5 * (minC[0] + maxC[0]), cv = 0.5 * (minC[1] + maxC[1]);
  const top = maxC[2] + margin, depthRange = maxC[2] - minC[2] + 2 * margin;
  // clip x = (p.u - cu) / half, y = (p.v - cv) / half, z = 2 (top - p.d) / range - 1
  const projection = new Matrix4().set(
    u.x / half, u.y / half, u.z / half, -cu / half,
    v.x / half, v.y / half, v.z / half, -cv / half,
    -2 * d.x / depthRange, -2 * d.y / depthRange, -2 * d.z / depthRange, 2 * top / depthRange - 1,
    0, 0, 0, 1);
  const toUnit = new Matrix4().set(0.5, 0, 0, 0.5, 0, 0.5, 0, 0.5, 0, 0, 0.5, 0.5, 0, 0, 0, 1);
  return { projection, shadowMatrix: toUnit.multiply(projection), texel: 2 * half / size, depthRange };
}
