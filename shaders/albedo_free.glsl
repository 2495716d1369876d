// pass: prt_diffuse and prt_cpca with TEXTURED (their vertex stages); mirrors the albedo split of docs/conventions.md.
// ("Albedo and textures"): a vertex's shaded value divided by the albedo it was baked with, per
// channel; 0 where that albedo is 0 (the texture is black over the footprint).
layout(location = 2) in vec3 vertex_albedo;

vec3 albedo_free(vec3 shaded) {
  vec3 out_value;
  for (int c = 0; c < 3; ++c) out_value[c] = vertex_albedo[c] > 0.0 ? shaded[c] / vertex_albedo[c] : 0.0;
  return out_value;
}
