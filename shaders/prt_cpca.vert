// pass: prt_cpca, vertex stage: the radiance prt_cpca.comp wrote for this vertex; mirrors prt_diffuse.vert's output.
#version 450 core

layout(location = 0) in vec3 position;
layout(std430, binding = 9) readonly buffer Radiance { vec4 vertex_radiance[]; };

uniform mat4 model_view_projection;

out vec3 radiance;

void main() {
  radiance = vertex_radiance[gl_VertexID].rgb;
  gl_Position = model_view_projection * vec4(position, 1.0);
}
