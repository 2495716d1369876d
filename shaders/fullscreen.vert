// pass: background and tonemap (one triangle covering the viewport); mirrors Renderer::draw_background / Renderer::present.
#version 450 core

// Normalised device coordinates of the fragment, (-1,-1) bottom left to (1,1) top right.
out vec2 ndc;

void main() {
  vec2 corner = vec2(gl_VertexID == 1 ? 3.0 : -1.0, gl_VertexID == 2 ? 3.0 : -1.0);
  ndc = corner;
  gl_Position = vec4(corner, 0.0, 1.0);
}
