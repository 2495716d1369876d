// pass: sun (visibility at the vertices, for tests); mirrors prt::shade::disc_visibility.
// disc_visibility of sun_light.glsl at each vertex's position and normal, exactly what the fragment
// passes evaluate there.
#version 450 core

layout(local_size_x = 64) in;

layout(std430, binding = 4) readonly buffer Positions { float positions[]; };
layout(std430, binding = 5) readonly buffer Normals { float normals[]; };
layout(std430, binding = 6) writeonly buffer Visibility { float visibility[]; };
uniform int vertex_count;
uniform int disc;

#include "sun_light.glsl"

void main() {
  int v = int(gl_GlobalInvocationID.x);
  if (v >= vertex_count) return;
  vec3 p = vec3(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);
  vec3 n = normalize(vec3(normals[3 * v], normals[3 * v + 1], normals[3 * v + 2]));
  visibility[v] = disc_visibility(disc, p, n);
}
