// pass: prt_lightmap_cpca (compressed texels, shaded once per lighting change), compute; mirrors prt::compress::decompress + prt::shade::shade_diffuse.
// Every non-empty texel: the blend of prt::render::cpca_products as prt::compress::decompress blends the
// vectors, shaded as prt::shade::shade_diffuse (and, with the discs, shade_diffuse_split's sky + bounce part).
// The CPU computes each cluster's N + 1 products (mean, then the PCA directions) with the object-frame
// lighting (renderer_lightmap_cpca.h); texel p of cluster k with weights w gets P_k0 + sum_n w_n P_k(n+1),
// written to its texel of level 0 of the shaded lightmap (rgb; a = 1: filled, for the mip chain).
#version 450 core

layout(local_size_x = 64) in;

// #defined by the pass: PCA, N weights per texel; HALF_WEIGHTS for a float16 model.
const int pca = PCA;

// This frame's products, rgb per texel of an RGBA32F buffer texture: k * (pca + 1) + j.
layout(binding = 0) uniform samplerBuffer products;
layout(std430, binding = 7) readonly buffer Clusters { uint clusters[]; };  // per point, < K
#ifdef HALF_WEIGHTS  // #defined by the pass for a float16 model: two IEEE binary16 weights per uint
const int pairs = (pca + 1) / 2;
layout(std430, binding = 8) readonly buffer Weights { uint weights[]; };    // per point, ceil(N / 2)
float weight(int p, int n) {
  vec2 two = unpackHalf2x16(weights[p * pairs + n / 2]);
  return (n % 2) == 0 ? two.x : two.y;
}
#else
layout(std430, binding = 8) readonly buffer Weights { float weights[]; };   // per point, N
float weight(int p, int n) { return weights[p * pca + n]; }
#endif
layout(std430, binding = 9) readonly buffer Texels { uint texels[]; };      // per point: y W + x
layout(rgba32f, binding = 0) uniform writeonly image2D shaded_level;        // level 0, W x H

uniform int point_count;
uniform int width;  // W

void main() {
  int p = int(gl_GlobalInvocationID.x);
  if (p >= point_count) return;
  int base = int(clusters[p]) * (pca + 1);
  vec3 sum = texelFetch(products, base).rgb;
  for (int n = 0; n < pca; ++n) sum += weight(p, n) * texelFetch(products, base + n + 1).rgb;
  int t = int(texels[p]);
  imageStore(shaded_level, ivec2(t % width, t / width), vec4(sum, 1.0));
}
