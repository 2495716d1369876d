// pass: sun shadow maps (depth only, one layer per disc); mirrors Renderer's shadow_matrix (renderer_sun.cpp).
#version 450 core

layout(location = 0) in vec3 position;

uniform mat4 light_projection;  // mesh coordinates -> clip space of the disc's orthographic view

void main() { gl_Position = light_projection * vec4(position, 1.0); }
