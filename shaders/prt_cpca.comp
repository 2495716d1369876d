// pass: prt_cpca, compute stage (per-vertex radiance of CPCA-compressed PRT); mirrors prt::render::cpca_products + the blend of
// prt::compress::decompress, shaded as prt::shade::shade_diffuse / shade_glossy at the vertex.
// Per frame the CPU computes, for every cluster k and each of its N + 1 vectors (mean, then the PCA
// directions), the product with the object-frame lighting (glossy: then through the BRDF matrix B), so
// the products are outgoing radiance (diffuse) or outgoing radiance coefficients (glossy). A vertex
// of cluster k with weights w blends them: P_k0 + sum_n w_n P_k(n+1); glossy vertices then evaluate
// the coefficients toward the eye in their local frame; the radiance goes to a storage buffer that
// prt_cpca.vert reads (one invocation per vertex, whatever the index list).
#version 450 core

layout(local_size_x = 64) in;

// #defined by Renderer::cpca_program:
//   PCA        N, weights per vertex
//   OUT_BANDS  0 for diffuse transfer; else the glossy transfer's output bands
const int pca = PCA;
const int out_bands = OUT_BANDS;
const int out_count = OUT_BANDS == 0 ? 1 : OUT_BANDS * OUT_BANDS;

// This frame's products, rgb per texel (an RGBA32F buffer texture): ((k * (pca + 1) + j) * out_count + o).
layout(binding = 0) uniform samplerBuffer products;
layout(std430, binding = 7) readonly buffer Clusters { uint clusters[]; };
layout(std430, binding = 8) readonly buffer Weights { float weights[]; };
layout(std430, binding = 4) readonly buffer Positions { float positions[]; };
layout(std430, binding = 5) readonly buffer Normals { float normals[]; };
layout(std430, binding = 9) writeonly buffer Radiance { vec4 radiance[]; };

uniform vec3 eye_object;  // glossy: the eye point in mesh coordinates
uniform int vertex_count;

#if OUT_BANDS > 0
// The local frame of prt::brdf::shading_frame (as prt_glossy.frag): returns F^T v.
vec3 to_local(vec3 n, vec3 v) {
  float length_xz = sqrt(n.z * n.z + n.x * n.x);
  vec3 t = length_xz >= 1e-6 ? vec3(n.z, 0.0, -n.x) / length_xz : normalize(vec3(1.0 - n.x * n.x, -n.x * n.y, -n.x * n.z));
  vec3 b = cross(n, t);
  return vec3(dot(t, v), dot(b, v), dot(n, v));
}

// sum over l < out_bands of O_lm Y_lm(d) (prt::sh::eval; the recurrence of prt_glossy.frag).
vec3 radiance_toward(vec3 coefficients[out_count], vec3 d) {
  vec3 sum = vec3(0.0);
  float n_mm = 0.28209479177387814;
  float cos_m = 1.0, sin_m = 0.0;
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
      int centre = l * (l + 1);
      if (m == 0) {
        sum += current * coefficients[centre];
      } else {
        sum += 1.4142135623730951 * current * (cos_m * coefficients[centre + m] + sin_m * coefficients[centre - m]);
      }
    }
  }
  return sum;
}
#endif

vec3 load3(int which, int i) {
  return which == 0 ? vec3(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2])
                    : vec3(normals[3 * i], normals[3 * i + 1], normals[3 * i + 2]);
}

void main() {
  int v = int(gl_GlobalInvocationID.x);
  if (v >= vertex_count) return;
  int base = int(clusters[v]) * (pca + 1) * out_count;
  float w[pca];
  for (int n = 0; n < pca; ++n) w[n] = weights[v * pca + n];
#if OUT_BANDS == 0
  vec3 sum = texelFetch(products, base).rgb;
  for (int n = 0; n < pca; ++n) sum += w[n] * texelFetch(products, base + n + 1).rgb;
  radiance[v] = vec4(sum, 1.0);
#else
  vec3 coefficients[out_count];
  for (int o = 0; o < out_count; ++o) {
    vec3 sum = texelFetch(products, base + o).rgb;
    for (int n = 0; n < pca; ++n) sum += w[n] * texelFetch(products, base + (n + 1) * out_count + o).rgb;
    coefficients[o] = sum;
  }
  vec3 position = load3(0, v);
  radiance[v] = vec4(radiance_toward(coefficients, to_local(load3(1, v), normalize(eye_object - position))), 1.0);
#endif
}
