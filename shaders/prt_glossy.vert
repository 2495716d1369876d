// pass: prt_glossy, vertex stage (passes mesh coordinates on); mirrors the rasterisation of tests/render/cpu_raster.h.
// The fragment stage evaluates each corner's outgoing radiance toward the eye.
#version 450 core

layout(location = 0) in vec3 position;

uniform mat4 model_view_projection;
#ifdef SUN
invariant gl_Position;  // the same depth as the prepass (shadow.vert)
#endif

out vec3 object_position;  // mesh coordinates, interpolated perspective-correctly

void main() {
  object_position = position;
  gl_Position = model_view_projection * vec4(position, 1.0);
}
