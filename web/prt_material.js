// The PRT material of one baked mesh (a three.js ShaderMaterial; three compiles it as GLSL ES 3.00), per vertex: the vertex
// stage blends its cluster's shaded values (prt_transfer.js, clusterProducts) with its PCA weights, as
// shaders/prt_cpca.comp does; the fragment stage applies the base colour (textured scenes), the discs'
// direct light (prt_sun.js) and three's tone mapping and output encoding (set them with
// probes/threejs/prt_tone_map.js for prt's display transform).
import { Color, Matrix3, ShaderMaterial, UniformsUtils } from 'three';
import { SUN_GLSL, SURFACE_VERTEX_GLSL } from './prt_sun.js';

function vertexShader(terms, attributes, uvName) {
  const weights = [];
  for (let a = 0; a < attributes; a++) weights.push(`in vec4 _prt_weights${a};`);
  const blend = [];
  for (let j = 1; j <= terms; j++) blend.push(`  r += _prt_weights${(j - 1) >> 2}[${(j - 1) & 3}] * prt_product(base + ${j});`);
  return /* glsl */ `
uniform highp sampler2D prt_products;
in float _prt_cluster;
in vec3 _prt_albedo;
${weights.join('\n')}
#if defined(PRT_UV1) && !defined(USE_UV1)
in vec2 uv1;
#endif
out vec3 prt_radiance;
out vec3 prt_albedo;
out vec3 prt_tint;
out vec2 prt_uv;
uniform mat3 prt_map_transform;
${SURFACE_VERTEX_GLSL}

vec3 prt_product(int t) {
  int width = textureSize(prt_products, 0).x;
  return texelFetch(prt_products, ivec2(t % width, t / width), 0).rgb;
}

void main() {
  int base = int(_prt_cluster + 0.5) * ${terms + 1};
  vec3 r = prt_product(base);
${blend.join('\n')}
#ifdef PRT_TEXTURED
  // The albedo split: radiance / baked albedo per channel (0 where the albedo is 0), interpolated.
  r = mix(vec3(0.0), r / max(_prt_albedo, vec3(1e-30)), greaterThan(_prt_albedo, vec3(0.0)));
#endif
  prt_radiance = r;
  prt_albedo = _prt_albedo;
#if defined(USE_COLOR) || defined(USE_COLOR_ALPHA)
  prt_tint = color.rgb;
#else
  prt_tint = vec3(1.0);
#endif
  prt_uv = (prt_map_transform * vec3(${uvName}, 1.0)).xy;
  gl_Position = prt_surface();
}`;
}

const FRAGMENT = /* glsl */ `
${SUN_GLSL}
uniform vec3 prt_factor;
#ifdef PRT_MAP
uniform sampler2D prt_map;
#endif
in vec3 prt_radiance;
in vec3 prt_albedo;
in vec3 prt_tint;
in vec2 prt_uv;
in vec3 prt_world_position;
in vec3 prt_world_normal;

void main() {
  // The base colour at the pixel, as prt's renderer (shaders/base_texture.glsl): factor x COLOR_0 x
  // texture (mip level 0, the sampler's filter and wrap), clamped to [0, 1].
  vec3 base = prt_factor * prt_tint;
#ifdef PRT_MAP
  vec2 uv = prt_uv;
  if (any(isnan(uv)) || any(isinf(uv))) uv = vec2(0.0);
  base *= textureLod(prt_map, uv, 0.0).rgb;
#endif
  base = clamp(base, 0.0, 1.0);
#ifdef PRT_TEXTURED
  vec3 radiance = prt_radiance * base;
  vec3 albedo = base;
#else
  vec3 radiance = prt_radiance;
  vec3 albedo = prt_albedo;
#endif
  if (disc_count > 0) {
    vec3 n = normalize(prt_world_normal);
    radiance = max(radiance + albedo * 0.31830988618379067 * prt_disc_light(prt_world_position, n), vec3(0.0));
  }
  gl_FragColor = vec4(radiance, 1.0);
  #include <tonemapping_fragment>
  #include <colorspace_fragment>
}`;

/// A PRT material for `mesh` (its geometry carries _PRT_CLUSTER, _PRT_WEIGHTS*, _PRT_ALBEDO) shading
/// `model` (its products texture). Keeps the old material's base colour: color, map (with its UV channel
/// and transform), vertex colours. options: {textured: apply the albedo split, sun: PrtSun}.
export function createPrtMaterial(mesh, model, { textured, sun }) {
  const old = mesh.material;
  const geometry = mesh.geometry;
  for (const name of ['_prt_cluster', '_prt_albedo', 'normal']) {
    if (!geometry.attributes[name]) throw new Error(`PRT_transfer: mesh '${mesh.name}' has no ${name} attribute`);
  }
  const attributes = Math.ceil(model.terms / 4);
  for (let a = 0; a < attributes; a++) {
    if (!geometry.attributes[`_prt_weights${a}`]) throw new Error(`PRT_transfer: mesh '${mesh.name}' has no _PRT_WEIGHTS${a} attribute`);
  }
  const map = old.map || null;
  const defines = {};
  if (textured) defines.PRT_TEXTURED = '';
  if (map) defines.PRT_MAP = '';
  if (map && map.channel === 1) defines.PRT_UV1 = '';
  if (map) map.updateMatrix();
  const material = new ShaderMaterial({
    defines,
    uniforms: UniformsUtils.merge([{
      prt_products: { value: null },
      prt_factor: { value: new Color(1, 1, 1) },
      prt_map: { value: null },
      prt_map_transform: { value: new Matrix3() },
      disc_shadows: { value: model.kind !== 'unshadowed' },
    }]),
    vertexShader: vertexShader(model.terms, attributes, map && map.channel === 1 ? 'uv1' : 'uv'),
    fragmentShader: FRAGMENT,
    vertexColors: !!geometry.attributes.color,
  });
  // Shared, not copied: the products and the discs change every frame for every material.
  material.uniforms.prt_products = { value: model.products };
  Object.assign(material.uniforms, sun.uniforms);
  material.uniforms.prt_factor.value.copy(old.color || new Color(1, 1, 1));
  material.uniforms.prt_map.value = map;
  if (map) material.uniforms.prt_map_transform.value.copy(map.matrix);
  material.name = `prt:${old.name || ''}`;
  material.side = old.side;
  return material;
}
