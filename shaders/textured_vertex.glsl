// pass: texture (included with TEXTURED by prt_diffuse.vert, prt_cpca.vert); mirrors the albedo split of docs/conventions.md.
// A textured mesh is drawn indexed over its draw vertices (render/textured_corners.h), each standing
// for the corners 3 t + k of one vertex with one base-colour UV and one material: draw_corner is the
// first of them, so the base-colour UV is the corner's own, not its vertex's, and the vertex stage runs
// once per draw vertex, not once per corner. The vertex's radiance is divided by
// the albedo it was baked with, per channel (0 where that is 0: the texture is black over the
// footprint); surface.frag multiplies the interpolated value by the base colour at the pixel.
// After base_material.glsl.
layout(std430, binding = 4) readonly buffer Positions { float positions[]; };
layout(std430, binding = 11) readonly buffer VertexAlbedo { float vertex_albedo[]; };
layout(location = 2) in uint draw_corner;  // a corner 3 t + k this draw vertex stands for
out vec2 corner_uv;       // transformed base-colour UV
flat out int corner_slot; // the material's texture slot (-1: none)
out vec3 corner_tint;     // factor x vertex colour

vec3 vertex_position(uint v) { return vec3(positions[3u * v], positions[3u * v + 1u], positions[3u * v + 2u]); }

vec3 albedo_free(vec3 shaded, uint v) {
  vec3 out_value;
  for (int c = 0; c < 3; ++c) {
    float albedo = vertex_albedo[3u * v + uint(c)];
    out_value[c] = albedo > 0.0 ? shaded[c] / albedo : 0.0;
  }
  return out_value;
}

// The base-colour inputs of corner `corner` (of vertex v) for the fragment stage.
void emit_corner(int corner, uint v) {
  Material m = materials[triangle_material[corner / 3]];
  corner_uv = material_uv(m, base_uv[corner]);
  corner_slot = m.slot.x;
  corner_tint = m.factor.rgb * vertex_colour_at(v);
}
