// pass: texture (included with TEXTURED by surface.frag and prt_sun.frag, before base_fragment.glsl); mirrors prt::mesh::sample_texture.
// The texture slots of a textured mesh (render/base_colour.h): TEXTURE_SLOTS (#defined, >= 1) units from
// 16, each an image with its glTF sampler (wrap modes; bilinear, or nearest for magFilter NEAREST; no
// mipmaps, so a lookup is the magnified texture's, as the conventions define it).
layout(binding = 16) uniform sampler2D base_textures[TEXTURE_SLOTS];

// The texture of `slot` at `uv` (transformed; a non-finite uv reads (0, 0)); 1 for slot -1.
vec3 sample_slot(int slot, vec2 uv) {
  if (any(isnan(uv)) || any(isinf(uv))) uv = vec2(0.0);
  vec3 colour = vec3(1.0);
  for (int k = 0; k < TEXTURE_SLOTS; ++k)
    if (slot == k) colour = textureLod(base_textures[k], uv, 0.0).rgb;
  return colour;
}

// A base colour clamped to [0, 1], NaN to 0.
vec3 clamp_colour(vec3 c) { return mix(clamp(c, 0.0, 1.0), vec3(0.0), isnan(c)); }
