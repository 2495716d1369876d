// pass: sun (shadow-map tile bounds); mirrors Renderer::draw_shadow_maps (renderer_sun.cpp).
// The least and greatest stored depth of every tile of shadow_tile x shadow_tile texels of each disc's
// map (sun_light.glsl's exact early-outs read them).
#version 450 core

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = 8) uniform sampler2DArray shadow_maps;
layout(rg32f, binding = 0) writeonly uniform image2DArray shadow_tiles;
uniform int shadow_tile;  // texels per tile side

void main() {
  ivec3 tile = ivec3(gl_GlobalInvocationID);
  ivec3 tiles = imageSize(shadow_tiles);
  if (tile.x >= tiles.x || tile.y >= tiles.y) return;
  float least = 1.0, greatest = 0.0;
  for (int y = 0; y < shadow_tile; ++y)
    for (int x = 0; x < shadow_tile; ++x) {
      float d = texelFetch(shadow_maps, ivec3(tile.xy * shadow_tile + ivec2(x, y), tile.z), 0).r;
      least = min(least, d);
      greatest = max(greatest, d);
    }
  imageStore(shadow_tiles, tile, vec4(least, greatest, 0.0, 0.0));
}
