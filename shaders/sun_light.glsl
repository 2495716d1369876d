// pass: sun (included by prt_sun.frag, prt_glossy.frag with SUN, sun_visibility.comp); mirrors prt::brdf::eval_cosine.
// The discs' uniforms, their shadow maps filtered PCSS-style (docs/conventions.md, "Sun shadow maps";
// set by Renderer::bind_sun, renderer_sun.cpp), and the BRDF evaluated exactly.

const int max_discs = 4;
const float inv_pi = 0.31830988618379067;
uniform int disc_count;
uniform vec3 disc_direction[max_discs];   // unit, mesh coordinates, toward the light
uniform vec3 disc_irradiance[max_discs];  // E per channel (irradiance at normal incidence)
uniform float disc_tan_radius[max_discs]; // tan of the angular radius
uniform mat4 shadow_matrix[max_discs];    // mesh coordinates -> (u, v, depth) in [0, 1]^3
uniform float shadow_depth_scale[max_discs];  // mesh units per unit of stored depth (the map's depth range)
uniform float shadow_texel[max_discs];        // mesh units per shadow-map texel
uniform bool disc_shadows;                // false for unshadowed transfer: V = 1 above the horizon
// Depth (0 nearest the light) of each disc's map, one layer per disc, and per tile of shadow_tile^2
// texels its least and greatest depth (shadow_minmax.comp).
layout(binding = 8) uniform sampler2DArray shadow_maps;
layout(binding = 9) uniform sampler2DArray shadow_tiles;
uniform int shadow_tile;

uniform int filter_count;  // the PCSS filter's samples (12, Renderer::bind_sun; a uniform: sun_pcss.glsl)

// Stored depth of map k at uv: the nearest texel, floor(uv * size); outside the map the border, 1
// (nothing in the way). The sampler's own border test is cheaper on llvmpipe than testing the texel
// index before a texelFetch.
float map_depth(int k, vec2 uv) { return textureLod(shadow_maps, vec3(uv, float(k)), 0.0).r; }

#include "sun_pcss.glsl"

// The BRDF as prt::brdf::terms: up to max_terms (shape, parameter, rgb weight); shapes as brdf::Shape
// (0 lambert, 1 phong, 2 blinn-phong, 3 ggx_f0, 4 ggx_edge, 5 lambert_fresnel). Set for glossy transfer only.
// With BRDF_TABLE defined, a table of BRDFs (one per vertex, Renderer::set_brdfs): BRDF b's term t is
// brdf_terms[2 (b max_terms + t)] = (shape, parameter, term count, 0) and the next entry (rgb weight, 0);
// else one BRDF in uniforms (index b ignored).
const int max_terms = 8;
#ifdef BRDF_TABLE
layout(std430, binding = 8) readonly buffer BrdfTerms { vec4 brdf_terms[]; };
int brdf_terms_of(uint b) { return int(brdf_terms[2u * b * uint(max_terms)].z); }
int brdf_shape_of(uint b, int t) { return int(brdf_terms[2u * (b * uint(max_terms) + uint(t))].x); }
float brdf_parameter_of(uint b, int t) { return brdf_terms[2u * (b * uint(max_terms) + uint(t))].y; }
vec3 brdf_weight_of(uint b, int t) { return brdf_terms[2u * (b * uint(max_terms) + uint(t)) + 1u].rgb; }
#else
uniform int brdf_term_count;
uniform int brdf_shape[max_terms];
uniform float brdf_parameter[max_terms];
uniform vec3 brdf_weight[max_terms];
int brdf_terms_of(uint b) { return brdf_term_count; }
int brdf_shape_of(uint b, int t) { return brdf_shape[t]; }
float brdf_parameter_of(uint b, int t) { return brdf_parameter[t]; }
vec3 brdf_weight_of(uint b, int t) { return brdf_weight[t]; }
#endif

// prt::brdf::eval_shape: local frame (+z the normal), w_i.z > 0, w_o mirrored to the upper side.
float brdf_shape_value(int shape, float parameter, vec3 w_i, vec3 w_o_signed) {
  vec3 w_o = vec3(w_o_signed.xy, abs(w_o_signed.z));
  if (shape == 0) return inv_pi;
  if (shape == 1) {
    float r_dot_o = -w_i.x * w_o.x - w_i.y * w_o.y + w_i.z * w_o.z;
    return (parameter + 2.0) * 0.5 * inv_pi * (r_dot_o > 0.0 ? pow(r_dot_o, parameter) : 0.0);
  }
  vec3 sum = w_i + w_o;
  float len = length(sum);
  if (!(len > 0.0)) return 0.0;
  vec3 h = sum / len;
  if (shape == 2) return (parameter + 8.0) * 0.125 * inv_pi * pow(min(1.0, h.z), parameter);
  if (shape == 5) {
    float m = max(0.0, 1.0 - min(1.0, dot(w_i, h)));
    return 0.96 * (1.0 - m * m * m * m * m) * inv_pi;
  }
  float alpha = parameter * parameter, alpha2 = alpha * alpha;
  float denominator = h.z * h.z * (alpha2 - 1.0) + 1.0;
  float d = alpha2 * inv_pi / (denominator * denominator);
  float cos_i = max(w_i.z, 0.0), cos_o = max(w_o.z, 0.0);
  float lambda_sum = cos_o * sqrt(cos_i * cos_i * (1.0 - alpha2) + alpha2) + cos_i * sqrt(cos_o * cos_o * (1.0 - alpha2) + alpha2);
  if (!(lambda_sum > 0.0)) return 0.0;
  float one_minus = max(0.0, 1.0 - min(1.0, dot(w_i, h)));
  float s5 = one_minus * one_minus * one_minus * one_minus * one_minus;
  return d * (0.5 / lambda_sum) * (shape == 3 ? 1.0 - s5 : s5);
}

// prt::brdf::eval_cosine of BRDF b (see BRDF_TABLE above): fbar(w_i, w_o) max(w_i.z, 0) per channel.
vec3 brdf_eval_cosine_of(uint b, vec3 w_i, vec3 w_o) {
  if (!(w_i.z > 0.0)) return vec3(0.0);
  vec3 sum = vec3(0.0);
  int count = brdf_terms_of(b);
  for (int t = 0; t < count; ++t) sum += brdf_weight_of(b, t) * brdf_shape_value(brdf_shape_of(b, t), brdf_parameter_of(b, t), w_i, w_o);
  return sum * w_i.z;
}

// The one BRDF's (uniforms).
vec3 brdf_eval_cosine(vec3 w_i, vec3 w_o) { return brdf_eval_cosine_of(0u, w_i, w_o); }

// prt::brdf::shading_frame's local coordinates of v for the unit normal n: (t . v, b . v, n . v) with
// t = normalize(Y x n) (X made orthogonal to n at the poles), b = n x t.
vec3 shading_local(vec3 n, vec3 v) {
  float length_xz = sqrt(n.z * n.z + n.x * n.x);
  vec3 t = length_xz >= 1e-6 ? vec3(n.z, 0.0, -n.x) / length_xz : normalize(vec3(1.0 - n.x * n.x, -n.x * n.y, -n.x * n.z));
  vec3 b = cross(n, t);
  return vec3(dot(t, v), dot(b, v), dot(n, v));
}
