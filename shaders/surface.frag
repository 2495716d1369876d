// pass: prt_diffuse and lambert (mesh surface); mirrors Renderer::read_radiance / Renderer::read_triangle_ids.
#version 450 core

in vec3 radiance;  // interpolated perspective-correctly from the vertices
#ifdef TEXTURED
// A textured mesh (textured_vertex.glsl): the radiance is albedo-free; times the base colour here.
#include "base_texture.glsl"
#include "base_fragment.glsl"
#endif
layout(location = 0) out vec4 radiance_out;
layout(location = 1) out uint triangle_out;
// The first mesh triangle of this draw (frame_core.h draw_runs: a pass drawing some runs of triangles);
// gl_PrimitiveID counts from 0 in every draw. 0 for a draw of the whole mesh.
uniform uint first_triangle;

void main() {
#ifdef TEXTURED
  radiance_out = vec4(radiance * pixel_base_colour(), 1.0);
#else
  radiance_out = vec4(radiance, 1.0);
#endif
  triangle_out = first_triangle + uint(gl_PrimitiveID);  // index of the triangle in the mesh's index list
}
