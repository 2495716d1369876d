// Included by the passes that shade discs (prt_sun.frag, prt_glossy.frag with SUN, sun_visibility.comp):
// the discs' uniforms, their shadow maps filtered PCSS-style, and the BRDF evaluated exactly.
// Mirrors Renderer's sun pass (renderer_sun.cpp) and docs/conventions.md, "Sun shadow maps".

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
// Depth (0 nearest the light) of each disc's map, one layer per disc.
layout(binding = 8) uniform sampler2DArray shadow_maps;

// Bias (docs/conventions.md, "Sun shadow maps"): the receiver moves along its normal by
// normal_offset texels x sin(theta), and a map depth d sampled r texels away counts as a blocker only
// when d < receiver - texel (constant_bias + (slope_bias + r) min(tan(theta), max_slope)).
const float normal_offset = 0.5, constant_bias = 0.5, slope_bias = 0.5, max_slope = 8.0;
// Search and filter radii are clamped to [min_filter, max_filter] texels.
const float min_filter = 0.75, max_filter = 12.0;

// A fixed spiral of 12 points in the unit disc (Vogel's golden-angle spiral, radius sqrt((i + 0.5) / 12)).
const vec2 spiral[12] = vec2[12](
    vec2(0.2041, 0.0000), vec2(-0.2607, 0.2388), vec2(0.0399, -0.4547), vec2(0.3286, 0.4286),
    vec2(-0.6030, -0.1067), vec2(0.5712, -0.3634), vec2(-0.1911, 0.7107), vec2(-0.3644, -0.7016),
    vec2(0.7906, 0.2887), vec2(-0.8224, 0.3395), vec2(0.3965, -0.8472), vec2(0.2930, 0.9341));

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
  float texels_per_unit = 1.0 / texel, texel_uv = 1.0 / float(textureSize(shadow_maps, 0).x);
  float search = clamp(receiver * disc_tan_radius[k] * texels_per_unit, min_filter, max_filter);
  float blocker_sum = 0.0, blockers = 0.0;
  for (int i = 0; i < 12; ++i) {
    float d = texture(shadow_maps, vec3(s.xy + spiral[i] * (search * texel_uv), float(k))).r * depth_scale;
    if (d < receiver - bias - bias_per_texel * length(spiral[i]) * search) {
      blocker_sum += d;
      blockers += 1.0;
    }
  }
  if (blockers == 0.0) return 1.0;
  float penumbra = clamp((receiver - blocker_sum / blockers) * disc_tan_radius[k] * texels_per_unit, min_filter, max_filter);
  float lit = 0.0;
  for (int i = 0; i < 12; ++i) {
    vec2 uv = s.xy + spiral[i] * (penumbra * texel_uv);
    float d = texture(shadow_maps, vec3(uv, float(k))).r * depth_scale;
    lit += d < receiver - bias - bias_per_texel * length(spiral[i]) * penumbra ? 0.0 : 1.0;
  }
  return lit / 12.0;
}

// The BRDF as prt::brdf::terms: up to max_terms (shape, parameter, rgb weight); shapes as brdf::Shape
// (0 lambert, 1 phong, 2 blinn-phong, 3 ggx_f0, 4 ggx_edge). Set for glossy transfer only.
const int max_terms = 8;
uniform int brdf_term_count;
uniform int brdf_shape[max_terms];
uniform float brdf_parameter[max_terms];
uniform vec3 brdf_weight[max_terms];

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

// prt::brdf::eval_cosine: fbar(w_i, w_o) max(w_i.z, 0) per channel.
vec3 brdf_eval_cosine(vec3 w_i, vec3 w_o) {
  if (!(w_i.z > 0.0)) return vec3(0.0);
  vec3 sum = vec3(0.0);
  for (int t = 0; t < brdf_term_count; ++t) sum += brdf_weight[t] * brdf_shape_value(brdf_shape[t], brdf_parameter[t], w_i, w_o);
  return sum * w_i.z;
}

// prt::brdf::shading_frame's local coordinates of v for the unit normal n: (t . v, b . v, n . v) with
// t = normalize(Y x n) (X made orthogonal to n at the poles), b = n x t.
vec3 shading_local(vec3 n, vec3 v) {
  float length_xz = sqrt(n.z * n.z + n.x * n.x);
  vec3 t = length_xz >= 1e-6 ? vec3(n.z, 0.0, -n.x) / length_xz : normalize(vec3(1.0 - n.x * n.x, -n.x * n.y, -n.x * n.z));
  vec3 b = cross(n, t);
  return vec3(dot(t, v), dot(b, v), dot(n, v));
}
