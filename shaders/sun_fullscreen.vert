// pass: sun (the deferred disc pass over the mesh's pixels); mirrors Renderer::draw_sun_deferred (renderer_sun.cpp).
// One triangle covering the viewport at the far plane (window depth 1): with the depth test GREATER
// it reaches exactly the pixels the mesh covered (depth < 1), and the depth test skips the rest
// before the fragment stage runs.
#version 450 core

void main() {
  vec2 corner = vec2(gl_VertexID == 1 ? 3.0 : -1.0, gl_VertexID == 2 ? 3.0 : -1.0);
  gl_Position = vec4(corner, 1.0, 1.0);
}
