// pass: texture (included with TEXTURED by prt_diffuse.vert, prt_cpca.vert, prt_sun.frag); mirrors prt::mesh::TriangleColour.
// The materials of a textured mesh as render/base_colour.h uploads them (docs/conventions.md, "Albedo
// and textures"): per material its factor (rgb), its KHR_texture_transform as an affine map, u' =
// dot(transform_u.xyz, (u, v, 1)) and v' likewise, and the texture slot it samples (slot.x; -1: none).
struct Material {
  vec4 factor;
  vec4 transform_u;
  vec4 transform_v;
  ivec4 slot;
};
layout(std430, binding = 3) readonly buffer Indices { uint indices[]; };
layout(std430, binding = 12) readonly buffer Materials { Material materials[]; };
layout(std430, binding = 13) readonly buffer BaseUv { vec2 base_uv[]; };              // per triangle corner
layout(std430, binding = 14) readonly buffer TriangleMaterial { uint triangle_material[]; };
layout(std430, binding = 15) readonly buffer VertexColour { float vertex_colour[]; };  // rgb per vertex
uniform bool has_vertex_colour;

// COLOR_0 of vertex v (1 without vertex colours).
vec3 vertex_colour_at(uint v) {
  return has_vertex_colour ? vec3(vertex_colour[3u * v], vertex_colour[3u * v + 1u], vertex_colour[3u * v + 2u]) : vec3(1.0);
}

// A base-colour UV through the material's transform.
vec2 material_uv(Material m, vec2 uv) {
  vec3 h = vec3(uv, 1.0);
  return vec2(dot(m.transform_u.xyz, h), dot(m.transform_v.xyz, h));
}
