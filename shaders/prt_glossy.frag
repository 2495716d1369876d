// pass: prt_glossy, fragment stage (corners' outgoing radiance toward the eye); mirrors prt::shade::shade_glossy.
// Per fragment: the radiance toward the eye of each corner of the triangle, each evaluated in that
// corner's own local frame, blended with the fragment's barycentrics (renderer.h, prt_glossy; the CPU
// reference is tests/render/test_render_glossy.cpp).
#version 450 core

// #defined by Renderer::glossy_draw_program:
//   OUT_BANDS   bands of the outgoing radiance coefficients (the transfer's bands_out)
//   SUN         (defined only with discs) add each disc's direct light: the BRDF evaluated exactly in the
//               interpolated normal's shading frame, times E V (prt::shade::disc_direct_glossy)
//   BRDF_TABLE  (with SUN, several BRDFs) each corner's own BRDF (vertex_brdf), the values blended with
//               the fragment's barycentrics as the corners' transferred radiance is
const int out_bands = OUT_BANDS;
const int out_count = OUT_BANDS * OUT_BANDS;

in vec3 object_position;
layout(location = 0) out vec4 radiance_out;
layout(location = 1) out uint triangle_out;

// Written by prt_glossy.comp this frame: out_count rgb coefficients per vertex, local frame.
layout(std430, binding = 2) readonly buffer Outgoing { vec4 outgoing[]; };
// The mesh: triangle corner indices, positions and unit normals (x, y, z per vertex, packed).
layout(std430, binding = 3) readonly buffer Indices { uint indices[]; };
layout(std430, binding = 4) readonly buffer Positions { float positions[]; };
layout(std430, binding = 5) readonly buffer Normals { float normals[]; };

uniform vec3 eye_object;  // the eye point in mesh coordinates
#ifdef SUN
#include "sun_light.glsl"
#endif
#ifdef BRDF_TABLE
layout(std430, binding = 7) readonly buffer VertexBrdf { uint vertex_brdf[]; };
#endif

vec3 load3(int which, uint i) {
  return which == 0 ? vec3(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2])
                    : vec3(normals[3 * i], normals[3 * i + 1], normals[3 * i + 2]);
}

// The local frame of prt::brdf::shading_frame: t = normalize(Y x n) (X made orthogonal to n at the
// poles), b = n x t; returns F^T v.
vec3 to_local(vec3 n, vec3 v) {
  float length_xz = sqrt(n.z * n.z + n.x * n.x);
  vec3 t = length_xz >= 1e-6 ? vec3(n.z, 0.0, -n.x) / length_xz : normalize(vec3(1.0 - n.x * n.x, -n.x * n.y, -n.x * n.z));
  vec3 b = cross(n, t);
  return vec3(dot(t, v), dot(b, v), dot(n, v));
}

// sum over l < out_bands of O_lm Y_lm(d) for vertex `vertex` (prt::sh::eval; the recurrence of
// background.frag's sh_radiance).
vec3 radiance_toward(uint vertex, vec3 d) {
  int first = int(vertex) * out_count;
  vec3 sum = vec3(0.0);
  float n_mm = 0.28209479177387814;
  float cos_m = 1.0, sin_m = 0.0;  // Re and Im of (x + i y)^m
  for (int m = 0; m < out_bands; ++m) {
    if (m > 0) {
      n_mm *= -sqrt(float(2 * m + 1) / float(2 * m));
      float c = cos_m * d.x - sin_m * d.y;
      sin_m = sin_m * d.x + cos_m * d.y;
      cos_m = c;
    }
    float previous = 0.0, current = n_mm;
    for (int l = m; l < out_bands; ++l) {
      if (l == m + 1) {
        previous = current;
        current = sqrt(float(2 * m + 3)) * d.z * n_mm;
      } else if (l > m + 1) {
        float fl = float(l), fm = float(m);
        float a = sqrt((4.0 * fl * fl - 1.0) / (fl * fl - fm * fm));
        float b = sqrt(((fl - 1.0) * (fl - 1.0) - fm * fm) / (4.0 * (fl - 1.0) * (fl - 1.0) - 1.0));
        float next = a * (d.z * current - b * previous);
        previous = current;
        current = next;
      }
      int centre = first + l * (l + 1);
      if (m == 0) {
        sum += current * outgoing[centre].rgb;
      } else {
        sum += 1.4142135623730951 * current * (cos_m * outgoing[centre + m].rgb + sin_m * outgoing[centre - m].rgb);
      }
    }
  }
  return sum;
}

void main() {
  uint triangle = uint(gl_PrimitiveID);
  uint corner[3] = uint[3](indices[3u * triangle], indices[3u * triangle + 1u], indices[3u * triangle + 2u]);
  // Barycentrics of the fragment's point in its triangle's plane.
  vec3 p0 = load3(0, corner[0]);
  vec3 e1 = load3(0, corner[1]) - p0, e2 = load3(0, corner[2]) - p0, d = object_position - p0;
  float d00 = dot(e1, e1), d01 = dot(e1, e2), d11 = dot(e2, e2), d20 = dot(d, e1), d21 = dot(d, e2);
  float denominator = d00 * d11 - d01 * d01;
  float b1 = (d11 * d20 - d01 * d21) / denominator, b2 = (d00 * d21 - d01 * d20) / denominator;
  float weight[3] = float[3](1.0 - b1 - b2, b1, b2);
  vec3 view = normalize(eye_object - object_position);
  vec3 sum = vec3(0.0);
  for (int c = 0; c < 3; ++c) sum += weight[c] * radiance_toward(corner[c], to_local(load3(1, corner[c]), view));
#ifdef SUN
  vec3 n = normalize(weight[0] * load3(1, corner[0]) + weight[1] * load3(1, corner[1]) + weight[2] * load3(1, corner[2]));
  vec3 w_o = shading_local(n, view);
  for (int k = 0; k < disc_count; ++k) {
    if (dot(n, disc_direction[k]) <= 0.0) continue;  // back-facing: no light, no shadow lookup
    vec3 w_i = shading_local(n, disc_direction[k]);
#ifdef BRDF_TABLE
    vec3 f = vec3(0.0);
    for (int c = 0; c < 3; ++c) f += weight[c] * brdf_eval_cosine_of(vertex_brdf[corner[c]], w_i, w_o);
#else
    vec3 f = brdf_eval_cosine(w_i, w_o);
#endif
    sum += disc_irradiance[k] * f * disc_visibility(k, object_position, n);
  }
  sum = max(sum, vec3(0.0));  // as split shading clamps
#endif
  radiance_out = vec4(sum, 1.0);
  triangle_out = triangle;
}
