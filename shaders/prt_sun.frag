// pass: prt_diffuse with discs (SUN), fragment stage; mirrors prt::shade::shade_diffuse_split.
// The interpolated PRT radiance plus each disc's direct light per pixel, (albedo / pi) E max(n . l, 0) V
// (prt::shade::disc_direct_diffuse).
#version 450 core

in vec3 radiance;         // PRT (sky and the discs' bounce light), interpolated
in vec3 object_position;  // mesh coordinates
in vec3 object_normal;    // interpolated vertex normal
in vec3 surface_albedo;   // the albedo the transfer was baked with
layout(location = 0) out vec4 radiance_out;
layout(location = 1) out uint triangle_out;

#include "sun_light.glsl"

void main() {
  vec3 n = normalize(object_normal);
  vec3 direct = vec3(0.0);
  for (int k = 0; k < disc_count; ++k) {
    float cos_theta = dot(n, disc_direction[k]);
    if (cos_theta <= 0.0) continue;  // back-facing: no light, no shadow lookup
    direct += disc_irradiance[k] * (cos_theta * disc_visibility(k, object_position, n));
  }
  radiance_out = vec4(max(radiance + surface_albedo * inv_pi * direct, vec3(0.0)), 1.0);  // as split shading clamps
  triangle_out = uint(gl_PrimitiveID);
}
