// pass: prt_cpca (glossy) with discs (SUN), fragment stage; mirrors prt::shade::shade_glossy_split.
// The interpolated per-vertex PRT radiance (sky and the discs' bounce light, prt_cpca.comp) plus each
// disc's direct light per pixel: E fbar(F^T d, F^T v) max(n . d, 0) V in the interpolated normal's
// shading frame, as prt_glossy.frag with SUN (prt::shade::disc_direct_glossy).
#version 450 core

in vec3 radiance;         // PRT toward the eye, per vertex, interpolated
in vec3 object_position;  // mesh coordinates
in vec3 object_normal;    // interpolated vertex normal
layout(location = 0) out vec4 radiance_out;
layout(location = 1) out uint triangle_out;

uniform vec3 eye_object;  // the eye point in mesh coordinates

#include "sun_light.glsl"

void main() {
  vec3 n = normalize(object_normal);
  vec3 w_o = shading_local(n, normalize(eye_object - object_position));
  vec3 sum = radiance;
  for (int k = 0; k < disc_count; ++k) {
    if (dot(n, disc_direction[k]) <= 0.0) continue;  // back-facing: no light, no shadow lookup
    sum += disc_irradiance[k] * brdf_eval_cosine(shading_local(n, disc_direction[k]), w_o) * disc_visibility(k, object_position, n);
  }
  radiance_out = vec4(max(sum, vec3(0.0)), 1.0);  // as split shading clamps
  triangle_out = uint(gl_PrimitiveID);
}
