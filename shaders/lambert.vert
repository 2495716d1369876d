// pass: lambert (baseline without PRT: one directional light); mirrors prt::render::lambert_light.
#version 450 core

layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec3 albedo;

uniform mat4 model_view_projection;
uniform mat3 normal_to_world;   // the object's rotation
uniform vec3 light_direction;   // unit, world frame, toward the light
uniform vec3 light_radiance;    // mean radiance of the lighting: E = pi * light_radiance at normal incidence

out vec3 radiance;

void main() {
  vec3 n = normalize(normal_to_world * normal);
  // Lambert: albedo / pi * E cos = albedo * light_radiance * cos.
  radiance = albedo * light_radiance * max(dot(n, light_direction), 0.0);
  gl_Position = model_view_projection * vec4(position, 1.0);
}
