// pass: sun, deferred over the mesh's pixels after prt_diffuse (SUN); mirrors prt::shade::shade_diffuse_split.
// Per pixel, once: the PRT radiance the mesh draw left (sky and the discs' bounce light) plus each
// disc's direct light, (albedo / pi) E max(n . l, 0) V (prt::shade::disc_direct_diffuse), clamped at 0
// as split shading clamps. The surface point is where the pixel's ray meets the triangle the mesh draw
// recorded; normal and albedo are interpolated with its barycentrics, as the rasteriser interpolates
// them perspective-correctly at the pixel centre. Shading each covered pixel exactly once, rather than
// in the mesh draw, matters on software rasterisers (llvmpipe), which run the fragment stage for every
// 2 x 2 quad a triangle touches, for hidden fragments and whatever branches decide.
#version 450 core

layout(binding = 11) uniform sampler2D frame_radiance;    // the mesh draw's radiance (attachment 0)
layout(binding = 12) uniform usampler2D frame_triangles;  // the mesh draw's triangle index (attachment 1)
// The mesh (Renderer::bind_sun_surface): per triangle its corner indices; per vertex three texels:
// position, normal, and the albedo the transfer was baked with.
layout(binding = 13) uniform usamplerBuffer triangle_corners;
layout(binding = 14) uniform samplerBuffer surface;
uniform vec2 frame_size;       // pixels
uniform vec3 eye_object;       // the eye, mesh coordinates
uniform mat3 ray_basis;        // ray direction (mesh coordinates) = ray_basis * (ndc x, ndc y, 1)
layout(location = 0) out vec4 radiance_out;

#include "sun_light.glsl"

// Texel `which` (0 position, 1 normal, 2 albedo) of vertex v.
vec3 load3(int which, uint v) { return texelFetch(surface, int(3u * v) + which).xyz; }

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec3 radiance = texelFetch(frame_radiance, pixel, 0).rgb;
  uint triangle = texelFetch(frame_triangles, pixel, 0).r;
  uvec3 corners = texelFetch(triangle_corners, int(triangle)).xyz;
  uint i0 = corners.x, i1 = corners.y, i2 = corners.z;
  vec3 p0 = load3(0, i0), p1 = load3(0, i1), p2 = load3(0, i2);
  vec3 direction = ray_basis * vec3(gl_FragCoord.xy / frame_size * 2.0 - 1.0, 1.0);
  vec3 e1 = p1 - p0, e2 = p2 - p0, face = cross(e1, e2);
  vec3 p = eye_object + direction * (dot(p0 - eye_object, face) / dot(direction, face));
  // Barycentrics of p (the rasteriser's perspective-correct weights at the pixel centre).
  vec3 q = p - p0;
  float d11 = dot(e1, e1), d12 = dot(e1, e2), d22 = dot(e2, e2), q1 = dot(q, e1), q2 = dot(q, e2);
  float inv = 1.0 / (d11 * d22 - d12 * d12);
  float b1 = (d22 * q1 - d12 * q2) * inv, b2 = (d11 * q2 - d12 * q1) * inv, b0 = 1.0 - b1 - b2;
  vec3 n = normalize(b0 * load3(1, i0) + b1 * load3(1, i1) + b2 * load3(1, i2));
  vec3 albedo = b0 * load3(2, i0) + b1 * load3(2, i1) + b2 * load3(2, i2);
  vec3 direct = vec3(0.0);
  for (int k = 0; k < disc_count; ++k) {
    float cos_theta = dot(n, disc_direction[k]);
    if (cos_theta <= 0.0) continue;  // back-facing: no light, no shadow lookup
    direct += disc_irradiance[k] * (cos_theta * disc_visibility(k, p, n));
  }
  radiance_out = vec4(max(radiance + albedo * inv_pi * direct, vec3(0.0)), 1.0);
}
