// pass: sun shadow maps (depth only, one layer per disc) and the SUN draws' depth prepass; mirrors Renderer::draw_shadow_maps and Renderer::draw_sun_prepass (renderer_sun.cpp).
#version 450 core

layout(location = 0) in vec3 position;

// mesh coordinates -> clip space of the disc's orthographic view (the maps), or of the camera (the
// depth prepass of the SUN draws, Renderer::draw_sun_prepass: invariant, as their vertex stages)
uniform mat4 light_projection;
invariant gl_Position;

void main() { gl_Position = light_projection * vec4(position, 1.0); }
