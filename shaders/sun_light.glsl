// pass: sun (included by prt_sun.frag, prt_glossy.frag with SUN, sun_visibility.comp); mirrors prt::brdf::eval_cosine.
// The discs' uniforms, their shadow maps filtered PCSS-style (docs/conventions.md, "Sun shadow maps";
// set by Renderer::bind_sun, renderer_sun.cpp), and the BRDF evaluated exactly.

// SUN_TILE_EARLY_OUTS 0 (Renderer on a software rasteriser, renderer_sun.cpp): no tile early-outs. They
// are exact (the same visibility either way) and save the lookups on a GPU, but a SIMD software
// rasteriser (llvmpipe) executes every instruction whatever a branch decides, so there they only cost.
#ifndef SUN_TILE_EARLY_OUTS
#define SUN_TILE_EARLY_OUTS 1
#endif
#ifndef SEARCH_COUNT
#define SEARCH_COUNT 8
#endif
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

// Bias (docs/conventions.md, "Sun shadow maps"): the receiver moves along its normal by
// normal_offset texels x sin(theta), and a map depth d sampled r texels away counts as a blocker only
// when d < receiver - texel (constant_bias + (slope_bias + r) min(tan(theta), max_slope)).
const float normal_offset = 0.5, constant_bias = 0.5, slope_bias = 0.5, max_slope = 8.0;
// Search and filter radii are clamped to [min_filter, max_filter] texels.
const float min_filter = 0.75, max_filter = 12.0;

// Vogel's golden-angle spiral in the unit disc (point i at radius sqrt((i + 0.5) / N), angle i times
// the golden angle): N = search_count for the blocker search (a fixed table, the loop unrolled: every
// pixel facing the disc takes all of it), N = filter_count for the filter (generated as it goes).
// filter_count is a uniform (12, Renderer::bind_sun), not a constant, so that the filter stays a loop:
// a SIMD software rasteriser (llvmpipe) runs every instruction of a branch whatever its lanes decide,
// but leaves a loop once no lane is left in it, so the blocks of 8 pixels in which none found a
// blocker (most of the lit surface) skip all but one of its iterations.
const int search_count = SEARCH_COUNT;
uniform int filter_count;
const float golden_angle = 2.39996322972865332;  // pi (3 - sqrt(5))
#if SEARCH_COUNT == 6
const vec2 search_spiral[6] = vec2[6](
    vec2(0.2887, 0.0000), vec2(-0.3687, 0.3377), vec2(0.0564, -0.6430), vec2(0.4647, 0.6061),
    vec2(-0.8528, -0.1508), vec2(0.8078, -0.5139));
#else
const vec2 search_spiral[8] = vec2[8](
    vec2(0.2500, 0.0000), vec2(-0.3193, 0.2925), vec2(0.0489, -0.5569), vec2(0.4024, 0.5249),
    vec2(-0.7385, -0.1306), vec2(0.6996, -0.4450), vec2(-0.2340, 0.8705), vec2(-0.4463, -0.8593));
#endif
// Stored depth of map k at uv: the nearest texel, floor(uv * size); outside the map the border, 1
// (nothing in the way). The sampler's own border test is cheaper on llvmpipe than testing the texel
// index before a texelFetch.
float map_depth(int k, vec2 uv) { return textureLod(shadow_maps, vec3(uv, float(k)), 0.0).r; }

// Fraction of disc k visible from the point p (mesh coordinates) with unit normal n: 0 when the disc's
// centre is below the tangent plane; else PCSS: a blocker search over the region a disc-sized cone
// from p meets at the top of the map, 1 if it finds no blocker, else PCF over the penumbra width
// (receiver depth - mean blocker depth) tan(radius).
float disc_visibility(int k, vec3 p, vec3 n) {
  vec3 l = disc_direction[k];
  float cos_theta = dot(n, l);
  if (cos_theta <= 0.0) return 0.0;
  if (!disc_shadows) return 1.0;
  float sin_theta = sqrt(max(0.0, 1.0 - cos_theta * cos_theta));
  float texel = shadow_texel[k], depth_scale = shadow_depth_scale[k];
  vec3 s = (shadow_matrix[k] * vec4(p + n * (normal_offset * texel * sin_theta), 1.0)).xyz;
  float receiver = s.z * depth_scale;
  // A sample r texels from the receiver's own texel may see the receiver's plane up to r tan(theta)
  // texels nearer the light: the bias grows with the sample's distance (receiver-plane bias, isotropic).
  float slope = min(sin_theta / cos_theta, max_slope);
  float bias = texel * (constant_bias + slope_bias * slope), bias_per_texel = texel * slope;
  float size = float(textureSize(shadow_maps, 0).x), texels_per_unit = 1.0 / texel, texel_uv = 1.0 / size;
  float search = clamp(receiver * disc_tan_radius[k] * texels_per_unit, min_filter, max_filter);
#if SUN_TILE_EARLY_OUTS
  // Exact early-outs from the tiles under the search square (at most 2 x 2 tiles: search <= max_filter
  // < shadow_tile / 2): no texel there nearer than the least threshold -> no blocker -> lit; every texel
  // nearer than the greatest threshold -> every search and filter sample a blocker -> 0.
  vec2 reach = vec2(search * texel_uv);
  vec2 t_lo = clamp(floor((s.xy - reach) * size / float(shadow_tile)), vec2(0.0), vec2(textureSize(shadow_tiles, 0).xy - 1));
  vec2 t_hi = clamp(floor((s.xy + reach) * size / float(shadow_tile)), vec2(0.0), vec2(textureSize(shadow_tiles, 0).xy - 1));
  vec2 b00 = texelFetch(shadow_tiles, ivec3(ivec2(t_lo), k), 0).rg, b11 = texelFetch(shadow_tiles, ivec3(ivec2(t_hi), k), 0).rg;
  vec2 b01 = texelFetch(shadow_tiles, ivec3(int(t_lo.x), int(t_hi.y), k), 0).rg;
  vec2 b10 = texelFetch(shadow_tiles, ivec3(int(t_hi.x), int(t_lo.y), k), 0).rg;
  float least = min(min(b00.x, b11.x), min(b01.x, b10.x)) * depth_scale;
  float greatest = max(max(b00.y, b11.y), max(b01.y, b10.y)) * depth_scale;
  bool inside = all(greaterThanEqual(s.xy - reach, vec2(0.0))) && all(lessThan(s.xy + reach, vec2(1.0)));
  if (least >= receiver - bias) return 1.0;
  if (inside && greatest < receiver - bias - bias_per_texel * search) return 0.0;
#endif
  float blocker_sum = 0.0, blockers = 0.0;
  for (int i = 0; i < search_count; ++i) {
    float d = map_depth(k, s.xy + search_spiral[i] * (search * texel_uv)) * depth_scale;
    if (d < receiver - bias - bias_per_texel * length(search_spiral[i]) * search) {
      blocker_sum += d;
      blockers += 1.0;
    }
  }
  if (blockers == 0.0) return 1.0;
  float penumbra = clamp((receiver - blocker_sum / blockers) * disc_tan_radius[k] * texels_per_unit, min_filter, max_filter);
  float lit = 0.0;
  vec2 along = vec2(1.0, 0.0);
  const vec2 turn = vec2(cos(golden_angle), sin(golden_angle));
  for (int i = 0; i < filter_count; ++i) {
    float r = sqrt((float(i) + 0.5) / float(filter_count));
    float d = map_depth(k, s.xy + along * (r * penumbra * texel_uv)) * depth_scale;
    lit += d < receiver - bias - bias_per_texel * r * penumbra ? 0.0 : 1.0;
    along = vec2(along.x * turn.x - along.y * turn.y, along.x * turn.y + along.y * turn.x);
  }
  return lit / float(filter_count);
}

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
