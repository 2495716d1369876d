// pass: texture, fragment stage (included with TEXTURED by surface.frag); mirrors prt::mesh::TriangleColour::at.
// Any pass whose vertex stage includes textured_vertex.glsl may include it, after base_texture.glsl.
// The base colour at the pixel from what textured_vertex.glsl's emit_corner passed on: the texture of
// the corners' slot at the interpolated transformed UV, times the interpolated factor x COLOR_0, clamped
// to [0, 1] (docs/conventions.md, "Albedo and textures").
in vec2 corner_uv;
flat in int corner_slot;
in vec3 corner_tint;

vec3 pixel_base_colour() { return clamp_colour(corner_tint * sample_slot(corner_slot, corner_uv)); }
