// pass: prt_lightmap_cpca (shaded lightmap's mip chain), compute; mirrors prt::render::next_mip_level.
// One step of the coverage-aware mip chain of the shaded lightmap, on the GPU, by the rule of
// lightmap_mips.h, which the uncompressed lightmap pass applies to its transfer layers. The rule is
// linear in the values for a fixed coverage, so the chain of the shaded texels equals the shading of
// the transfer's chain (up to float rounding). Alpha carries "filled" (1) or not (0); rgb is 0 where not filled.
//   REDUCE  (defined) source = level l, target = level l + 1 before dilation: the mean of the filled
//           children (the last row or column of an odd size also takes the leftover child)
//   else    source = that averaged level, target = level l + 1: unfilled texels with filled
//           8-neighbours take their mean (one round of dilation)
#version 450 core

layout(local_size_x = 8, local_size_y = 8) in;

layout(rgba32f, binding = 0) uniform readonly image2D source;
layout(rgba32f, binding = 1) uniform writeonly image2D target;

// Children of parent index p along an axis of `size` texels whose parent level has `parents`.
ivec2 children(int p, int size, int parents) {
  return ivec2(min(2 * p, size - 1), min(p == parents - 1 ? size - 1 : 2 * p + 1, size - 1));
}

void main() {
  ivec2 out_size = imageSize(target), in_size = imageSize(source);
  ivec2 t = ivec2(gl_GlobalInvocationID.xy);
  if (t.x >= out_size.x || t.y >= out_size.y) return;
  vec3 sum = vec3(0.0);
  int n = 0;
#ifdef REDUCE
  ivec2 cx = children(t.x, in_size.x, out_size.x), cy = children(t.y, in_size.y, out_size.y);
  for (int y = cy.x; y <= cy.y; ++y)
    for (int x = cx.x; x <= cx.y; ++x) {
      vec4 c = imageLoad(source, ivec2(x, y));
      if (c.a < 0.5) continue;
      ++n;
      sum += c.rgb;
    }
#else
  vec4 own = imageLoad(source, t);
  if (own.a >= 0.5) {
    imageStore(target, t, own);
    return;
  }
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      ivec2 c = t + ivec2(dx, dy);
      if (c.x < 0 || c.y < 0 || c.x >= in_size.x || c.y >= in_size.y) continue;
      vec4 v = imageLoad(source, c);
      if (v.a < 0.5) continue;
      ++n;
      sum += v.rgb;
    }
#endif
  imageStore(target, t, n == 0 ? vec4(0.0) : vec4(sum / float(n), 1.0));
}
