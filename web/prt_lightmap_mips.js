// A per-texel PRT_transfer primitive's radiance as a lightmap with prt render's mip chain, recomputed on
// the GPU when the lighting changes (PrtRelighting.update), so that the material samples it trilinearly as
// `prt render` samples its lightmap layers (docs/conventions.md, "Lightmap rendering"; the rule of
// src/render/lightmap_mips.h). Level 0: each texel's radiance s_k0 + sum_j w_j s_kj from the model's
// per-cluster shaded values (prt_transfer.js, clusterProducts), alpha 1 where the texel is covered or
// gutter, 0 (and radiance 0) where it is empty. Level l+1 (max(1, w/2) x max(1, h/2)): the mean of the
// FILLED children of level l (an odd size's last row or column takes the leftover child), filled if any
// child is; then one round of dilation: an unfilled texel with filled 8-neighbours takes their mean and is
// filled. The radiance of a mip texel is the same mean of its texels' radiance that prt's layer mips
// dotted with the lighting give (the chain is linear, its weights depend on coverage only).
import { ClampToEdgeWrapping, HalfFloatType, LinearFilter, LinearMipmapLinearFilter, Mesh, OrthographicCamera, PlaneGeometry,
         Scene, ShaderMaterial, WebGLRenderTarget } from 'three';

/// Levels of a w x h texture's full chain: 1 + floor(log2(max(w, h))) (lightmap_mips.h mip_level_count).
export function mipLevelCount(width, height) {
  let levels = 1;
  for (let side = Math.max(width, height); side > 1; side = Math.floor(side / 2)) levels++;
  return levels;
}

const FULLSCREEN_VERTEX = 'void main() { gl_Position = vec4(position.xy, 0.0, 1.0); }';

// Level 0: texel (x, y) of the lightmap at fragment (x, y).
function radianceShader(terms) {
  const fetches = [], blend = [];
  for (let a = 0; a < Math.ceil(terms / 4); a++) fetches.push(`  vec4 w${a} = texelFetch(prt_weights, ivec3(texel, ${a}), 0);`);
  for (let j = 1; j <= terms; j++) blend.push(`  r += w${(j - 1) >> 2}[${(j - 1) & 3}] * prt_product(base + ${j});`);
  return /* glsl */ `
precision highp sampler2DArray;
uniform highp sampler2D prt_products;
uniform sampler2DArray prt_cluster;
#if TERMS > 0
uniform sampler2DArray prt_weights;
#endif
vec3 prt_product(int t) {
  int width = textureSize(prt_products, 0).x;
  return texelFetch(prt_products, ivec2(t % width, t / width), 0).rgb;
}
void main() {
  ivec2 texel = ivec2(gl_FragCoord.xy);
  vec4 c = texelFetch(prt_cluster, ivec3(texel, 0), 0);
  if (c.g < 0.5) { gl_FragColor = vec4(0.0); return; }
  int base = int(c.r + 0.5) * ${terms + 1};
  vec3 r = prt_product(base);
${fetches.join('\n')}
${blend.join('\n')}
  gl_FragColor = vec4(r, 1.0);
}`;
}

// Level prt_level + 1 from level prt_level of prt_source: the mean of the filled children.
const AVERAGE = /* glsl */ `
uniform highp sampler2D prt_source;
uniform int prt_level;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy), size = textureSize(prt_source, prt_level), parents = max(size / 2, ivec2(1));
  ivec2 first = min(2 * p, size - 1);
  ivec2 last = min(ivec2(p.x == parents.x - 1 ? size.x - 1 : 2 * p.x + 1, p.y == parents.y - 1 ? size.y - 1 : 2 * p.y + 1), size - 1);
  vec3 sum = vec3(0.0);
  float n = 0.0;
  for (int dy = 0; dy < 3; ++dy) for (int dx = 0; dx < 3; ++dx) {
    ivec2 c = first + ivec2(dx, dy);
    if (c.x > last.x || c.y > last.y) continue;
    vec4 v = texelFetch(prt_source, c, prt_level);
    if (v.a > 0.5) { sum += v.rgb; n += 1.0; }
  }
  gl_FragColor = n > 0.0 ? vec4(sum / n, 1.0) : vec4(0.0);
}`;

// Level prt_level of prt_source dilated once: an unfilled texel takes the mean of its filled 8-neighbours.
const DILATE = /* glsl */ `
uniform highp sampler2D prt_source;
uniform int prt_level;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy), size = textureSize(prt_source, prt_level);
  vec4 own = texelFetch(prt_source, p, prt_level);
  if (own.a > 0.5) { gl_FragColor = own; return; }
  vec3 sum = vec3(0.0);
  float n = 0.0;
  for (int dy = -1; dy <= 1; ++dy) for (int dx = -1; dx <= 1; ++dx) {
    ivec2 c = p + ivec2(dx, dy);
    if (c.x < 0 || c.y < 0 || c.x >= size.x || c.y >= size.y) continue;
    vec4 v = texelFetch(prt_source, c, prt_level);
    if (v.a > 0.5) { sum += v.rgb; n += 1.0; }
  }
  gl_FragColor = n > 0.0 ? vec4(sum / n, 1.0) : vec4(0.0);
}`;

// A W x H RGBA16F target with every level of its chain allocated (one framebuffer per level).
function chainTarget(width, height, levels) {
  const target = new WebGLRenderTarget(width, height, {
    type: HalfFloatType, depthBuffer: false, generateMipmaps: false, minFilter: LinearMipmapLinearFilter, magFilter: LinearFilter,
    wrapS: ClampToEdgeWrapping, wrapT: ClampToEdgeWrapping,
  });
  target.texture.mipmaps = Array.from({ length: levels }, () => ({}));
  return target;
}

/// The radiance lightmap of one per-texel primitive: `texture` (trilinear, clamp to edge, rows as the
/// lightmap UVs address them) is rebuilt by update(renderer) from `model.products` (shared, updated first).
export class LightmapRadiance {
  constructor(lightmap, model) {
    const { width, height } = lightmap;
    this.width = width;
    this.height = height;
    this.levels = mipLevelCount(width, height);
    this.chain = chainTarget(width, height, this.levels);     // the result
    this.scratch = chainTarget(width, height, this.levels);   // each level before its dilation
    this.texture = this.chain.texture;
    const pass = (fragmentShader, uniforms, defines = {}) => new ShaderMaterial({ vertexShader: FULLSCREEN_VERTEX, fragmentShader, uniforms, defines, depthTest: false, depthWrite: false });
    this.radiance = pass(radianceShader(model.terms), {
      prt_products: { value: model.products }, prt_cluster: { value: lightmap.cluster }, prt_weights: { value: lightmap.weights },
    }, { TERMS: model.terms });
    this.average = pass(AVERAGE, { prt_source: { value: this.chain.texture }, prt_level: { value: 0 } });
    this.dilate = pass(DILATE, { prt_source: { value: this.scratch.texture }, prt_level: { value: 0 } });
    this.quad = new Mesh(new PlaneGeometry(2, 2), this.radiance);
    this.quad.frustumCulled = false;
    this.scene = new Scene().add(this.quad);
    this.camera = new OrthographicCamera();
  }

  // Draws `material` over level `level` of `target`.
  draw(renderer, material, target, level) {
    target.viewport.set(0, 0, Math.max(1, this.width >> level), Math.max(1, this.height >> level));
    this.quad.material = material;
    renderer.setRenderTarget(target, 0, level);
    renderer.render(this.scene, this.camera);
  }

  /// Recomputes every level (the products must be current); restores the renderer's render target.
  update(renderer) {
    const previous = renderer.getRenderTarget(), autoClear = renderer.autoClear;
    renderer.autoClear = false;
    this.draw(renderer, this.radiance, this.chain, 0);
    for (let level = 1; level < this.levels; level++) {
      this.average.uniforms.prt_level.value = level - 1;  // chain's level - 1 -> scratch's level
      this.draw(renderer, this.average, this.scratch, level);
      this.dilate.uniforms.prt_level.value = level;       // scratch's level -> chain's level
      this.draw(renderer, this.dilate, this.chain, level);
    }
    renderer.autoClear = autoClear;
    renderer.setRenderTarget(previous);
  }
}
