// pass: prt_diffuse (per-vertex diffuse PRT); mirrors prt::shade::shade_diffuse.
#version 450 core

// Compiled once per combination of these, #defined by Renderer::prt_program (constant loop bounds let
// the compiler unroll the loop and fold the channel test; measurably cheaper on llvmpipe):
//   CHANNELS           1 (grey transfer, shared by r, g, b) or 3
//   COEFFICIENT_COUNT  bands^2 of the transfer (its per-channel stride)
//   USED_COUNT         k^2: only the first k bands are used (truncation), k <= bands
//   CHUNKS             1..8 buffer-texture views the transfer is split into (see TransferBuffer)
//   SUN                (defined only with discs) add the discs' bounce light (per-vertex, computed when the
//                      lighting changes); their direct light is prt_sun.frag's deferred pass
//   TEXTURED           (a textured mesh, with TEXTURE_SLOTS) drawn per draw vertex (vertex, UV, material), the radiance divided
//                      by the vertex's albedo, the base colour multiplied per pixel (textured_vertex.glsl)
const int channels = CHANNELS;
const int coefficient_count = COEFFICIENT_COUNT;
const int used_count = USED_COUNT;

#ifdef TEXTURED
#include "base_material.glsl"
#include "textured_vertex.glsl"
#else
layout(location = 0) in vec3 position;
#endif

// The transfer file's values, vertex-major (vertex v's block of channels * coefficient_count floats,
// channel-major inside), one float per texel (GL_R32F views of one buffer). View k holds vertices
// [k * vertices_per_chunk, (k + 1) * vertices_per_chunk).
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

// Lighting in the object's frame (rotated on the CPU), rgb per coefficient, flat index l(l+1)+m.
layout(std140, binding = 0) uniform Lighting { vec4 lighting[1024]; };

uniform mat4 model_view_projection;

out vec3 radiance;
#ifdef SUN
// Per vertex, x y z packed: the discs' bounce light.
layout(std430, binding = 7) readonly buffer SunBounce { float sun_bounce[]; };
#endif

// sum += per channel, the dot product of the vertex's first used_count transfer coefficients with the
// lighting (a grey transfer multiplies all three lighting channels).
#define ACCUMULATE(values)                                                                       \
  for (int i = 0; i < used_count; ++i) {                                                         \
    vec3 t = channels == 3 ? vec3(texelFetch(values, base + i).r,                                 \
                                  texelFetch(values, base + coefficient_count + i).r,             \
                                  texelFetch(values, base + 2 * coefficient_count + i).r)         \
                           : vec3(texelFetch(values, base + i).r);                                \
    sum += t * lighting[i].rgb;                                                                   \
  }

void main() {
#ifdef TEXTURED
  int vertex = int(indices[draw_corner]);
  vec3 position = vertex_position(uint(vertex));
#else
  int vertex = gl_VertexID;
#endif
  int chunk = CHUNKS > 1 ? vertex / vertices_per_chunk : 0;
  int base = (vertex - chunk * vertices_per_chunk) * channels * coefficient_count;
  vec3 sum = vec3(0.0);
  if (chunk == 0) {
    ACCUMULATE(transfer0)
  }
#if CHUNKS > 1
  else if (chunk == 1) {
    ACCUMULATE(transfer1)
  }
#endif
#if CHUNKS > 2
  else if (chunk == 2) {
    ACCUMULATE(transfer2)
  }
#endif
#if CHUNKS > 3
  else if (chunk == 3) {
    ACCUMULATE(transfer3)
  }
#endif
#if CHUNKS > 4
  else if (chunk == 4) {
    ACCUMULATE(transfer4)
  }
#endif
#if CHUNKS > 5
  else if (chunk == 5) {
    ACCUMULATE(transfer5)
  }
#endif
#if CHUNKS > 6
  else if (chunk == 6) {
    ACCUMULATE(transfer6)
  }
#endif
#if CHUNKS > 7
  else if (chunk == 7) {
    ACCUMULATE(transfer7)
  }
#endif
#ifdef SUN
  int i3 = 3 * vertex;
  sum += vec3(sun_bounce[i3], sun_bounce[i3 + 1], sun_bounce[i3 + 2]);
#endif
#ifdef TEXTURED
  sum = albedo_free(sum, uint(vertex));
  emit_corner(int(draw_corner), uint(vertex));
#endif
  radiance = sum;
  gl_Position = model_view_projection * vec4(position, 1.0);
}
