// pass: prt_glossy, compute stage (O = B (M L) per vertex); mirrors prt::shade::glossy_outgoing_coefficients.
#version 450 core

// Compiled once per combination of these, #defined by Renderer::glossy_compute_program:
//   CHANNELS       1 (grey transfer, shared by r, g, b) or 3
//   IN_COUNT       bands^2 of the transfer's input (lighting) side: the row length of its matrices
//   USED_COUNT     k^2: only the first k lighting bands are used (truncation), k <= bands
//   OUT_COUNT      bands_out^2: matrix rows, and the size of the BRDF matrix B (OUT_COUNT x OUT_COUNT)
//   CHUNKS         1..8 buffer-texture views the transfer is split into (see TransferBuffer)
//   BRDF_TABLE     (defined only with several BRDFs) vertex v uses B number vertex_brdf[v] of the table
//   SUN            (defined only with discs) add the discs' bounce coefficients B (M_bounce L_discs),
//                  computed by this same program when the lighting changes, into O
const int channels = CHANNELS;
const int in_count = IN_COUNT;
const int used_count = USED_COUNT;
const int out_count = OUT_COUNT;

layout(local_size_x = 64) in;

// The transfer file's values, vertex-major: vertex v's block is channels matrices of out_count x
// in_count floats, row-major [out][in]. View k holds vertices [k * vertices_per_chunk, ...).
layout(binding = 0) uniform samplerBuffer transfer0;
#if CHUNKS > 1
layout(binding = 1) uniform samplerBuffer transfer1;
#endif
#if CHUNKS > 2
layout(binding = 2) uniform samplerBuffer transfer2;
#endif
#if CHUNKS > 3
layout(binding = 3) uniform samplerBuffer transfer3;
#endif
#if CHUNKS > 4
layout(binding = 4) uniform samplerBuffer transfer4;
#endif
#if CHUNKS > 5
layout(binding = 5) uniform samplerBuffer transfer5;
#endif
#if CHUNKS > 6
layout(binding = 6) uniform samplerBuffer transfer6;
#endif
#if CHUNKS > 7
layout(binding = 7) uniform samplerBuffer transfer7;
#endif
uniform int vertices_per_chunk;
uniform int vertex_count;

// Lighting in the object's frame (rotated on the CPU), rgb per coefficient, flat index l(l+1)+m.
layout(std140, binding = 0) uniform Lighting { vec4 lighting[1024]; };
// The BRDF matrix B, row-major [out k][in j], rgb per entry (a grey B repeated in r, g, b); with
// BRDF_TABLE several such matrices back to back, and each vertex's index into them.
layout(std430, binding = 1) readonly buffer BrdfMatrix { vec4 brdf[]; };
#ifdef BRDF_TABLE
layout(std430, binding = 7) readonly buffer VertexBrdf { uint vertex_brdf[]; };
#endif
// Output: out_count rgb coefficients per vertex (w unused), vertex-major, local frame of the vertex.
layout(std430, binding = 2) writeonly buffer Outgoing { vec4 outgoing[]; };
#ifdef SUN
layout(std430, binding = 6) readonly buffer BounceOutgoing { vec4 bounce_outgoing[]; };
#endif

float fetch(int chunk, int index) {
#if CHUNKS > 1
  if (chunk == 1) return texelFetch(transfer1, index).r;
#endif
#if CHUNKS > 2
  if (chunk == 2) return texelFetch(transfer2, index).r;
#endif
#if CHUNKS > 3
  if (chunk == 3) return texelFetch(transfer3, index).r;
#endif
#if CHUNKS > 4
  if (chunk == 4) return texelFetch(transfer4, index).r;
#endif
#if CHUNKS > 5
  if (chunk == 5) return texelFetch(transfer5, index).r;
#endif
#if CHUNKS > 6
  if (chunk == 6) return texelFetch(transfer6, index).r;
#endif
#if CHUNKS > 7
  if (chunk == 7) return texelFetch(transfer7, index).r;
#endif
  return texelFetch(transfer0, index).r;
}

void main() {
  int v = int(gl_GlobalInvocationID.x);
  if (v >= vertex_count) return;
  int chunk = CHUNKS > 1 ? v / vertices_per_chunk : 0;
  int base = (v - chunk * vertices_per_chunk) * channels * out_count * in_count;
  // T = M L: the transferred incident radiance (local frame), per colour channel.
  vec3 t[out_count];
  for (int k = 0; k < out_count; ++k) {
    vec3 sum = vec3(0.0);
    int row = base + k * in_count;
    for (int j = 0; j < used_count; ++j) {
      vec3 m = channels == 3 ? vec3(fetch(chunk, row + j), fetch(chunk, row + out_count * in_count + j),
                                    fetch(chunk, row + 2 * out_count * in_count + j))
                             : vec3(fetch(chunk, row + j));
      sum += m * lighting[j].rgb;
    }
    t[k] = sum;
  }
  // O = B T.
#ifdef BRDF_TABLE
  int first = int(vertex_brdf[v]) * out_count * out_count;
#else
  int first = 0;
#endif
  for (int k = 0; k < out_count; ++k) {
    vec3 sum = vec3(0.0);
    for (int j = 0; j < out_count; ++j) sum += brdf[first + k * out_count + j].rgb * t[j];
#ifdef SUN
    sum += bounce_outgoing[v * out_count + k].rgb;
#endif
    outgoing[v * out_count + k] = vec4(sum, 0.0);
  }
}
