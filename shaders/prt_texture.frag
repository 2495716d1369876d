// pass: texture, deferred over a textured mesh's pixels; mirrors prt::mesh::base_color times the albedo-free radiance.
// After a per-vertex diffuse draw without discs (with discs prt_sun.frag with TEXTURED does the same),
// the albedo split (docs/conventions.md, "Albedo and textures"): the draw left the interpolated
// albedo-free radiance, this multiplies it by the base colour at the pixel.
#version 450 core

layout(binding = 11) uniform sampler2D frame_radiance;    // the mesh draw's radiance (attachment 0)
layout(binding = 12) uniform usampler2D frame_triangles;  // the mesh draw's triangle index (attachment 1)
layout(std430, binding = 4) readonly buffer Positions { float positions[]; };
layout(location = 0) out vec4 radiance_out;

#include "pixel_surface.glsl"
#include "base_colour.glsl"

vec3 position_at(uint v) { return vec3(positions[3u * v], positions[3u * v + 1u], positions[3u * v + 2u]); }

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec3 radiance = texelFetch(frame_radiance, pixel, 0).rgb;
  uint t = texelFetch(frame_triangles, pixel, 0).r;
  vec3 p;
  vec3 b = pixel_barycentrics(position_at(indices[3u * t]), position_at(indices[3u * t + 1u]), position_at(indices[3u * t + 2u]), p);
  radiance_out = vec4(radiance * base_colour(t, b), 1.0);
}
