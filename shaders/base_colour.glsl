// pass: texture (included by prt_texture.frag, prt_sun.frag with TEXTURED); mirrors prt::mesh::TriangleColour::at.
// The base colour at a point of a triangle, the texture filtered as prt::mesh::sample_texture
// (docs/conventions.md, "Albedo and textures"). The mesh's materials, base-colour UVs and textures as render/base_colour.h uploads them.

// Per material: factor (rgb); the affine KHR_texture_transform, u' = dot(transform_u.xyz, (u, v, 1)),
// v' likewise; image = (first texel in `texels`, width, height, 1 if textured else 0); sampler = (wrap
// along u, wrap along v: 0 repeat, 1 clamp to edge, 2 mirrored repeat; 1 for the nearest filter).
struct Material {
  vec4 factor;
  vec4 transform_u;
  vec4 transform_v;
  ivec4 image;
  ivec4 sampler;
};
layout(std430, binding = 3) readonly buffer Indices { uint indices[]; };
layout(std430, binding = 12) readonly buffer Materials { Material materials[]; };
layout(std430, binding = 13) readonly buffer BaseUv { vec2 base_uv[]; };              // per triangle corner
layout(std430, binding = 14) readonly buffer TriangleMaterial { uint triangle_material[]; };
layout(std430, binding = 15) readonly buffer VertexColour { float vertex_colour[]; };  // rgb per vertex
layout(binding = 15) uniform samplerBuffer texels;  // every texture's rows from the top, one after another
uniform bool has_vertex_colour;

// Texel index i of an axis of n texels, wrapped by `mode`.
int wrap_texel(float i, int n, int mode) {
  if (mode == 1) return int(clamp(i, 0.0, float(n - 1)));
  if (mode == 0) return int(i - float(n) * floor(i / float(n)));
  int k = int(i - float(2 * n) * floor(i / float(2 * n)));  // in [0, 2n)
  return k < n ? k : 2 * n - 1 - k;
}

vec3 texel_at(Material m, float x, float y) {
  int ix = wrap_texel(x, m.image.y, m.sampler.x), iy = wrap_texel(y, m.image.z, m.sampler.y);
  return texelFetch(texels, m.image.x + iy * m.image.y + ix).rgb;
}

vec3 sample_material(Material m, vec2 uv) {
  if (any(isnan(uv)) || any(isinf(uv))) uv = vec2(0.0);
  float x = uv.x * float(m.image.y), y = uv.y * float(m.image.z);
  if (m.sampler.z == 1) return texel_at(m, floor(x), floor(y));
  float x0 = floor(x - 0.5), y0 = floor(y - 0.5);
  float fx = x - 0.5 - x0, fy = y - 0.5 - y0;
  vec3 top = (1.0 - fx) * texel_at(m, x0, y0) + fx * texel_at(m, x0 + 1.0, y0);
  vec3 bottom = (1.0 - fx) * texel_at(m, x0, y0 + 1.0) + fx * texel_at(m, x0 + 1.0, y0 + 1.0);
  return (1.0 - fy) * top + fy * bottom;
}

vec3 vertex_colour_at(uint v) { return vec3(vertex_colour[3u * v], vertex_colour[3u * v + 1u], vertex_colour[3u * v + 2u]); }

// The base colour at barycentrics b (of corners 0, 1, 2) of triangle t, clamped to [0, 1], NaN 0.
vec3 base_colour(uint t, vec3 b) {
  Material m = materials[triangle_material[t]];
  vec3 colour = m.factor.rgb;
  if (m.image.w != 0) {
    vec3 uv = vec3(b.x * base_uv[3u * t] + b.y * base_uv[3u * t + 1u] + b.z * base_uv[3u * t + 2u], 1.0);
    colour *= sample_material(m, vec2(dot(m.transform_u.xyz, uv), dot(m.transform_v.xyz, uv)));
  }
  if (has_vertex_colour)
    colour *= b.x * vertex_colour_at(indices[3u * t]) + b.y * vertex_colour_at(indices[3u * t + 1u]) +
              b.z * vertex_colour_at(indices[3u * t + 2u]);
  return mix(clamp(colour, 0.0, 1.0), vec3(0.0), isnan(colour));
}
