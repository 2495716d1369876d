// pass: prt_diffuse and lambert (mesh surface); mirrors Renderer::read_radiance / Renderer::read_triangle_ids.
#version 450 core

in vec3 radiance;  // interpolated perspective-correctly from the vertices
layout(location = 0) out vec4 radiance_out;
layout(location = 1) out uint triangle_out;

void main() {
  radiance_out = vec4(radiance, 1.0);
  triangle_out = uint(gl_PrimitiveID);  // index of the triangle in the mesh's index list
}
