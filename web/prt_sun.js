// The discs (suns) of prt's split lighting in three.js: one orthographic depth map per disc (at most 4),
// fitted as `prt render` fits it (src/render/sun_light.cpp: looking along -d, its square fitted to the
// baked meshes' world bounds across d, its depth range to their extent along d, depth 0 nearest the
// light, both sides of every triangle occluding), and the GLSL that filters it for the disc's size
// (PCSS, docs/conventions.md "Sun shadow maps": normal offset, slope-scaled receiver-plane bias, an
// 8-sample blocker search and a 12-sample filter over golden-angle spirals, radii clamped to [0.75, 12]
// texels, nearest texels, depth 1 outside the map).
import { Box3, DataTexture, DepthTexture, DoubleSide, FloatType, Matrix4, NearestFilter, OrthographicCamera, RGBAFormat, ShaderMaterial,
         Vector3, WebGLRenderTarget } from 'three';

export const MAX_DISCS = 4;
export const SHADOW_MAP_SIZE = 2048;
const SHADOW_LAYER = 31;  // the baked meshes' layer: what the depth maps see

/// GLSL (ES 3.00) of the discs' uniforms and prt_disc_visibility(map, k, p, n): the fraction of disc k
/// visible from world point p with unit normal n (0 below the horizon). Mirrors shaders/sun_light.glsl
/// without its tile early-outs (exact: the same visibility either way).
export const SUN_GLSL = /* glsl */ `
const int prt_max_discs = ${MAX_DISCS};
uniform int prt_disc_count;
uniform vec3 prt_disc_direction[prt_max_discs];
uniform vec3 prt_disc_irradiance[prt_max_discs];
uniform float prt_disc_tan_radius[prt_max_discs];
uniform mat4 prt_shadow_matrix[prt_max_discs];
uniform float prt_shadow_depth_scale[prt_max_discs];
uniform float prt_shadow_texel[prt_max_discs];
uniform bool prt_disc_shadows;
uniform sampler2D prt_shadow_map0, prt_shadow_map1, prt_shadow_map2, prt_shadow_map3;
const float prt_normal_offset = 0.5, prt_constant_bias = 0.5, prt_slope_bias = 0.5, prt_max_slope = 8.0;
const float prt_min_filter = 0.75, prt_max_filter = 12.0;
const int prt_filter_count = 12;
const float prt_golden_angle = 2.39996322972865332;
const vec2 prt_search_spiral[8] = vec2[8](
    vec2(0.2500, 0.0000), vec2(-0.3193, 0.2925), vec2(0.0489, -0.5569), vec2(0.4024, 0.5249),
    vec2(-0.7385, -0.1306), vec2(0.6996, -0.4450), vec2(-0.2340, 0.8705), vec2(-0.4463, -0.8593));

float prt_map_depth(sampler2D map, vec2 uv) {
  if (any(lessThan(uv, vec2(0.0))) || any(greaterThanEqual(uv, vec2(1.0)))) return 1.0;
  return textureLod(map, uv, 0.0).r;
}

float prt_disc_visibility(sampler2D map, int k, vec3 p, vec3 n) {
  vec3 l = prt_disc_direction[k];
  float cos_theta = dot(n, l);
  if (cos_theta <= 0.0) return 0.0;
  if (!prt_disc_shadows) return 1.0;
  float sin_theta = sqrt(max(0.0, 1.0 - cos_theta * cos_theta));
  float texel = prt_shadow_texel[k], depth_scale = prt_shadow_depth_scale[k];
  vec3 s = (prt_shadow_matrix[k] * vec4(p + n * (prt_normal_offset * texel * sin_theta), 1.0)).xyz;
  float receiver = s.z * depth_scale;
  float slope = min(sin_theta / cos_theta, prt_max_slope);
  float bias = texel * (prt_constant_bias + prt_slope_bias * slope), bias_per_texel = texel * slope;
  float texel_uv = 1.0 / float(textureSize(map, 0).x), texels_per_unit = 1.0 / texel;
  float search = clamp(receiver * prt_disc_tan_radius[k] * texels_per_unit, prt_min_filter, prt_max_filter);
  float blocker_sum = 0.0, blockers = 0.0;
  for (int i = 0; i < 8; ++i) {
    float d = prt_map_depth(map, s.xy + prt_search_spiral[i] * (search * texel_uv)) * depth_scale;
    if (d < receiver - bias - bias_per_texel * length(prt_search_spiral[i]) * search) {
      blocker_sum += d;
      blockers += 1.0;
    }
  }
  if (blockers == 0.0) return 1.0;
  float penumbra = clamp((receiver - blocker_sum / blockers) * prt_disc_tan_radius[k] * texels_per_unit, prt_min_filter, prt_max_filter);
  float lit = 0.0;
  vec2 along = vec2(1.0, 0.0);
  vec2 turn = vec2(cos(prt_golden_angle), sin(prt_golden_angle));
  for (int i = 0; i < prt_filter_count; ++i) {
    float r = sqrt((float(i) + 0.5) / float(prt_filter_count));
    float d = prt_map_depth(map, s.xy + along * (r * penumbra * texel_uv)) * depth_scale;
    lit += d < receiver - bias - bias_per_texel * r * penumbra ? 0.0 : 1.0;
    along = vec2(along.x * turn.x - along.y * turn.y, along.x * turn.y + along.y * turn.x);
  }
  return lit / float(prt_filter_count);
}

// sum over the discs of E_k max(n.d_k, 0) V_k (the direct light before albedo / pi).
vec3 prt_disc_light(vec3 p, vec3 n) {
  vec3 sum = vec3(0.0);
  for (int k = 0; k < prt_max_discs; ++k) {
    if (k >= prt_disc_count) break;
    float cos_theta = dot(n, prt_disc_direction[k]);
    if (cos_theta <= 0.0) continue;
    float v = k == 0 ? prt_disc_visibility(prt_shadow_map0, 0, p, n) : k == 1 ? prt_disc_visibility(prt_shadow_map1, 1, p, n)
            : k == 2 ? prt_disc_visibility(prt_shadow_map2, 2, p, n) : prt_disc_visibility(prt_shadow_map3, 3, p, n);
    sum += prt_disc_irradiance[k] * (cos_theta * v);
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

/// The discs' uniforms (shared by every PRT material) and depth maps.
export class PrtSun {
  constructor(scene, meshes) {
    this.scene = scene;
    this.meshes = meshes;
    for (const mesh of meshes) mesh.layers.enable(SHADOW_LAYER);
    this.targets = [];
    this.camera = new OrthographicCamera();
    this.camera.matrixAutoUpdate = false;
    this.camera.layers.set(SHADOW_LAYER);
    this.depthMaterial = new ShaderMaterial({
      vertexShader: 'void main() { gl_Position = projectionMatrix * modelViewMatrix * vec4(position, 1.0); }',
      fragmentShader: 'void main() { gl_FragColor = vec4(1.0); }',
      side: DoubleSide,
    });
    const dummy = new DataTexture(new Float32Array([1, 1, 1, 1]), 1, 1, RGBAFormat, FloatType);
    dummy.needsUpdate = true;
    this.uniforms = {
      prt_disc_count: { value: 0 },
      prt_disc_direction: { value: Array.from({ length: MAX_DISCS }, () => new Vector3()) },
      prt_disc_irradiance: { value: Array.from({ length: MAX_DISCS }, () => new Vector3()) },
      prt_disc_tan_radius: { value: new Array(MAX_DISCS).fill(0) },
      prt_shadow_matrix: { value: Array.from({ length: MAX_DISCS }, () => new Matrix4()) },
      prt_shadow_depth_scale: { value: new Array(MAX_DISCS).fill(1) },
      prt_shadow_texel: { value: new Array(MAX_DISCS).fill(1) },
      prt_shadow_map0: { value: dummy }, prt_shadow_map1: { value: dummy },
      prt_shadow_map2: { value: dummy }, prt_shadow_map3: { value: dummy },
    };
    this.discs = [];
  }

  /// Discs in the world frame: [{direction (unit), irradiance [r, g, b], radius (radians)}], at most 4.
  setDiscs(discs) {
    if (discs.length > MAX_DISCS) throw new Error(`prt_sun: ${discs.length} discs; at most ${MAX_DISCS}`);
    this.discs = discs;
    const u = this.uniforms;
    u.prt_disc_count.value = discs.length;
    discs.forEach((d, k) => {
      u.prt_disc_direction.value[k].fromArray(d.direction).normalize();
      u.prt_disc_irradiance.value[k].fromArray(d.irradiance);
      u.prt_disc_tan_radius.value[k] = Math.tan(d.radius);
    });
  }

  target(k) {
    while (this.targets.length <= k) {
      const depthTexture = new DepthTexture(SHADOW_MAP_SIZE, SHADOW_MAP_SIZE, FloatType);
      depthTexture.minFilter = depthTexture.magFilter = NearestFilter;
      this.targets.push(new WebGLRenderTarget(SHADOW_MAP_SIZE, SHADOW_MAP_SIZE, { depthTexture, depthBuffer: true }));
    }
    return this.targets[k];
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
    this.discs.forEach((disc, k) => {
      const fit = fitMap(bounds, new Vector3().fromArray(disc.direction).normalize());
      this.camera.projectionMatrix.copy(fit.projection);
      this.camera.projectionMatrixInverse.copy(fit.projection).invert();
      this.uniforms.prt_shadow_matrix.value[k].copy(fit.shadowMatrix);
      this.uniforms.prt_shadow_texel.value[k] = fit.texel;
      this.uniforms.prt_shadow_depth_scale.value[k] = fit.depthRange;
      renderer.setRenderTarget(this.target(k));
      renderer.clear(true, true, false);
      renderer.render(this.scene, this.camera);
      this.uniforms[`prt_shadow_map${k}`].value = this.target(k).depthTexture;
    });
    this.meshes.forEach((mesh, i) => { mesh.material = materials[i]; });
    renderer.setRenderTarget(previous);
  }
}

// The orthographic view of sun_light.cpp's draw_maps for unit direction d over `bounds`.
function fitMap(bounds, d) {
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
  return { projection, shadowMatrix: toUnit.multiply(projection), texel: 2 * half / SHADOW_MAP_SIZE, depthRange };
}
