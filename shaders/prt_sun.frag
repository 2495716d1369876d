// pass: sun, deferred over the mesh's pixels after prt_diffuse (SUN); mirrors prt::shade::shade_diffuse_split.
// Per pixel, once: the PRT radiance the mesh draw left (sky and the discs' bounce light) plus each
// disc's direct light, (albedo / pi) E max(n . l, 0) V (prt::shade::disc_direct_diffuse), clamped at 0
// as split shading clamps. TEXTURED (a textured mesh, docs/conventions.md "Albedo and textures"): the
// direct light takes the base colour at the pixel as its albedo, as the mesh draw did.
// The surface point is where the pixel's ray meets the triangle the mesh draw recorded; normal and
// albedo are interpolated with its barycentrics, as the rasteriser interpolates them
// perspective-correctly at the pixel centre. Shading each covered pixel exactly once, rather than
// in the mesh draw, matters on software rasterisers (llvmpipe), which run the fragment stage for every
// 2 x 2 quad a triangle touches, for hidden fragments and whatever branches decide.
#version 450 core

layout(binding = 11) uniform sampler2D frame_radiance;    // the mesh draw's radiance (attachment 0)
layout(binding = 12) uniform usampler2D frame_triangles;  // the mesh draw's triangle index (attachment 1)
// The mesh (Renderer::bind_sun_surface): per triangle its corner indices; per vertex three texels:
// position, normal, and the albedo the transfer was baked with.
layout(binding = 13) uniform usamplerBuffer triangle_corners;
layout(binding = 14) uniform samplerBuffer surface;
layout(location = 0) out vec4 radiance_out;

#include "sun_light.glsl"
#include "pixel_surface.glsl"
#ifdef TEXTURED
#include "base_material.glsl"
#include "base_texture.glsl"

// The base colour at barycentrics b of triangle t (prt::mesh::TriangleColour::at).
vec3 base_colour(uint t, vec3 b) {
  Material m = materials[triangle_material[t]];
  vec2 uv = b.x * base_uv[3u * t] + b.y * base_uv[3u * t + 1u] + b.z * base_uv[3u * t + 2u];
  vec3 tint = b.x * vertex_colour_at(indices[3u * t]) + b.y * vertex_colour_at(indices[3u * t + 1u]) +
              b.z * vertex_colour_at(indices[3u * t + 2u]);
  return clamp_colour(m.factor.rgb * tint * sample_slot(m.slot.x, material_uv(m, uv)));
}
#endif

// Texel `which` (0 position, 1 normal, 2 albedo) of vertex v.
vec3 load3(int which, uint v) { return texelFetch(surface, int(3u * v) + which).xyz; }

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec3 radiance = texelFetch(frame_radiance, pixel, 0).rgb;
  uint triangle = texelFetch(frame_triangles, pixel, 0).r;
  uvec3 corners = texelFetch(triangle_corners, int(triangle)).xyz;
  uint i0 = corners.x, i1 = corners.y, i2 = corners.z;
  vec3 p0 = load3(0, i0), p1 = load3(0, i1), p2 = load3(0, i2);
  vec3 p;
  vec3 b = pixel_barycentrics(p0, p1, p2, p);
  float b0 = b.x, b1 = b.y, b2 = b.z;
  vec3 n = normalize(b0 * load3(1, i0) + b1 * load3(1, i1) + b2 * load3(1, i2));
#ifdef TEXTURED
  vec3 albedo = base_colour(triangle, b);  // the draw's radiance has it already (surface.frag)
#else
  vec3 albedo = b0 * load3(2, i0) + b1 * load3(2, i1) + b2 * load3(2, i2);
#endif
  vec3 direct = vec3(0.0);
  for (int k = 0; k < disc_count; ++k) {
    float cos_theta = dot(n, disc_direction[k]);
    if (cos_theta <= 0.0) continue;  // back-facing: no light, no shadow lookup
    direct += disc_irradiance[k] * (cos_theta * disc_visibility(k, p, n));
  }
  radiance_out = vec4(max(radiance + albedo * inv_pi * direct, vec3(0.0)), 1.0);
}
