// pass: prt_lightmap_cpca (compressed texels, per pixel), fragment stage; mirrors prt_lightmap.frag.
// With prt_lightmap.vert. As prt_lightmap.frag: there the transfer's texel blocks are filtered and then
// dotted with the lighting; here the texels were shaded first (prt_lightmap_cpca.comp, once per
// lighting change, and the coverage-aware mip chain lightmap_mip.comp) and are filtered as they are:
// the filter is linear, so both give the same radiance up to float rounding, and no cluster id is ever
// interpolated. With SUN, each disc's direct light per pixel and the clamp at 0, as prt_lightmap.frag.
#version 450 core

in vec2 texture_coordinate;
layout(location = 0) out vec4 radiance_out;
layout(location = 1) out uint triangle_out;

// The shaded texels (rgb: the sky's light, and with SUN the discs' bounce light), full mip chain.
layout(binding = 0) uniform sampler2D shaded_texels;

#ifdef SUN
in vec3 object_position;  // mesh coordinates
in vec3 object_normal;    // interpolated vertex normal
in vec3 surface_albedo;   // the albedo the transfer was baked with
#include "sun_light.glsl"
#endif

void main() {
#ifdef TEXEL_SPACE
  vec3 sum = textureLod(shaded_texels, texture_coordinate, 0.0).rgb;  // the texels themselves
#else
  vec3 sum = texture(shaded_texels, texture_coordinate).rgb;  // trilinear over the mip chain
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
  triangle_out = uint(gl_PrimitiveID);
}
