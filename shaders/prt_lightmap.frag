// pass: prt_lightmap (texel transfer, per-pixel), fragment stage; mirrors prt::shade::shade_diffuse (and,
// with SUN, shade_diffuse_split) applied to the bilinearly filtered transfer of the lightmap texels.
#version 450 core

// Compiled once per combination of these, #defined by Renderer::lightmap_program (constant loop bounds:
// the compiler unrolls the layer loop and folds the index arithmetic):
//   CHANNELS           1 (grey transfer, shared by r, g, b) or 3
//   COEFFICIENT_COUNT  bands^2 of the transfer (its per-channel stride)
//   USED_COUNT         k^2: only the first k bands are used (truncation), k <= bands
//   LAYERS             ceil(CHANNELS * COEFFICIENT_COUNT / 4) RGBA layers of the texture arrays
//   SUN                (defined only with discs) add each disc's direct light per pixel, as prt_sun.frag
//   BOUNCE             (with SUN, for interreflected transfer with a bounce-only section) add the discs'
//                      bounce light: the bounce-only layers dotted with the discs' SH
const int channels = CHANNELS;
const int coefficient_count = COEFFICIENT_COUNT;
const int used_count = USED_COUNT;
const int layers = LAYERS;

in vec2 texture_coordinate;
layout(location = 0) out vec4 radiance_out;
layout(location = 1) out uint triangle_out;
// The first mesh triangle of this draw (frame_core.h draw_runs); gl_PrimitiveID counts from 0 in every
// draw. 0 for a draw of the whole mesh.
uniform uint first_triangle;

// A texel's value block (channel-major, then SH index, as the .prt payload) packed four values per
// layer: layer k holds values 4k .. 4k+3 in r, g, b, a; the last layer is zero-padded
// (Renderer::add_lightmap, renderer_lightmap.h).
layout(binding = 0) uniform sampler2DArray transfer_layers;
// Lighting in the object's frame (rotated on the CPU), rgb per coefficient, flat index l(l+1)+m.
layout(std140, binding = 0) uniform Lighting { vec4 lighting[1024]; };

#ifdef BOUNCE
layout(binding = 1) uniform sampler2DArray bounce_layers;  // the bounce-only part, same layout
layout(std140, binding = 2) uniform DiscLighting { vec4 disc_lighting[1024]; };  // the discs' SH, object frame
#endif
#ifdef SUN
in vec3 object_position;  // mesh coordinates
in vec3 object_normal;    // interpolated vertex normal
in vec3 surface_albedo;   // the albedo the transfer was baked with
#include "sun_light.glsl"
#endif

// Render_texels (TEXEL_SPACE) reads level 0, the texels themselves; the camera's view filters
// trilinearly over the mip chain (renderer_lightmap.h).
#ifdef TEXEL_SPACE
#define SAMPLE(layers_sampler, p) textureLod(layers_sampler, p, 0.0)
#else
#define SAMPLE(layers_sampler, p) texture(layers_sampler, p)
#endif

// sum += per channel, the dot product of the first used_count coefficients of the filtered texel block
// of `layers_sampler` with the coefficients `light` (a grey transfer multiplies all three channels).
#define ACCUMULATE(layers_sampler, light)                                                    \
  for (int k = 0; k < layers; ++k) {                                                       \
    vec4 t = SAMPLE(layers_sampler, vec3(uv, float(k)));                                    \
    for (int j = 0; j < 4; ++j) {                                                           \
      int value = 4 * k + j;                                                                \
      int c = value / coefficient_count, i = value - c * coefficient_count;                 \
      if (c >= channels || i >= used_count) continue;                                       \
      if (channels == 1) sum += t[j] * light[i].rgb;                                        \
      else sum[c] += t[j] * light[i][c];                                                    \
    }                                                                                       \
  }

void main() {
  vec2 uv = texture_coordinate;  // texel rows are uploaded top row first: no flip (conventions.md)
  vec3 sum = vec3(0.0);
  ACCUMULATE(transfer_layers, lighting)
#ifdef BOUNCE
  ACCUMULATE(bounce_layers, disc_lighting)
#endif
#ifdef SUN
  vec3 n = normalize(object_normal);
  vec3 direct = vec3(0.0);
  for (int k = 0; k < disc_count; ++k) {
    float cos_theta = dot(n, disc_direction[k]);
    if (cos_theta <= 0.0) continue;  // back-facing: no light, no shadow lookup
    direct += disc_irradiance[k] * (cos_theta * disc_visibility(k, object_position, n));
  }
  sum = max(sum + surface_albedo * inv_pi * direct, vec3(0.0));  // as split shading clamps
#endif
  radiance_out = vec4(sum, 1.0);
  triangle_out = first_triangle + uint(gl_PrimitiveID);
}
