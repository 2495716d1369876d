// pass: prt_cpca, vertex stage: the radiance prt_cpca.comp wrote for this vertex; mirrors prt_diffuse.vert's output.
#version 450 core

layout(location = 0) in vec3 position;
layout(std430, binding = 9) readonly buffer Radiance { vec4 vertex_radiance[]; };

uniform mat4 model_view_projection;

out vec3 radiance;
#ifdef TEXTURED
// A textured mesh: albedo-free, the base colour multiplies it per pixel (prt_texture.frag, prt_sun.frag).
#include "albedo_free.glsl"
#endif
#ifdef SUN
// For the discs' direct light in prt_cpca_sun.frag (glossy; diffuse transfer gets it in the deferred
// prt_sun.frag pass); their bounce light is in the radiance already.
layout(location = 1) in vec3 normal;
out vec3 object_position;
out vec3 object_normal;
#endif

void main() {
  radiance = vertex_radiance[gl_VertexID].rgb;
#ifdef TEXTURED
  radiance = albedo_free(radiance);
#endif
#ifdef SUN
  object_position = position;
  object_normal = normal;
#endif
  gl_Position = model_view_projection * vec4(position, 1.0);
}
