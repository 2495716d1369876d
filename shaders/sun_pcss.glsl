// pass: sun (included by sun_light.glsl, loaded by web/prt_sun.js too); mirrors prt::shade::disc_visibility.
// The discs' shadow maps filtered PCSS-style for the disc's size (docs/conventions.md, "Sun shadow
// maps"), written in the common subset of GLSL 4.50 and GLSL ES 3.00 so that prt's GL renderer and the
// browser run one filter. The includer declares, before including it: the uniforms disc_direction[],
// disc_tan_radius[], shadow_matrix[], shadow_depth_scale[], shadow_texel[] (max_discs each), disc_shadows
// and filter_count, the sampler2DArray shadow_maps (one layer per disc: its size is the map's), and
// float map_depth(int k, vec2 uv) (the stored depth of map k, 1 outside the map); with
// SUN_TILE_EARLY_OUTS 1 also shadow_tiles and shadow_tile (shadow_minmax.comp).

// SUN_TILE_EARLY_OUTS 0 (Renderer on a software rasteriser, renderer_sun.cpp): no tile early-outs. They
// are exact (the same visibility either way) and save the lookups on a GPU, but a SIMD software
// rasteriser (llvmpipe) executes every instruction whatever a branch decides, so there they only cost.
#ifndef SUN_TILE_EARLY_OUTS
#define SUN_TILE_EARLY_OUTS 1
#endif
#ifndef SEARCH_COUNT
#define SEARCH_COUNT 8
#endif

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
