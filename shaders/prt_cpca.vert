// pass: prt_cpca, vertex stage: the radiance prt_cpca.comp wrote for this vertex; mirrors prt_diffuse.vert's output.
#version 450 core

#ifdef TEXTURED
// A textured mesh (TEXTURE_SLOTS): drawn per draw vertex (vertex, UV, material), albedo-free (textured_vertex.glsl).
#include "base_material.glsl"
#include "textured_vertex.glsl"
#else
layout(location = 0) in vec3 position;
#endif
layout(std430, binding = 9) readonly buffer Radiance { vec4 vertex_radiance[]; };

uniform mat4 model_view_projection;

out vec3 radiance;
#ifdef SUN
// For the discs' direct light in prt_cpca_sun.frag (glossy; diffuse transfer gets it in the deferred
// prt_sun.frag pass); their bounce light is in the radiance already.
layout(location = 1) in vec3 normal;
out vec3 object_position;
out vec3 object_normal;
#endif

void main() {
#ifdef TEXTURED
  uint vertex = indices[draw_corner];
  vec3 position = vertex_position(vertex);
  radiance = albedo_free(vertex_radiance[vertex].rgb, vertex);
  emit_corner(int(draw_corner), vertex);
#else
  radiance = vertex_radiance[gl_VertexID].rgb;
#endif
#ifdef SUN
  object_position = position;
  object_normal = normal;
#endif
  gl_Position = model_view_projection * vec4(position, 1.0);
}
