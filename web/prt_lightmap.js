// Per-texel (lightmap) transfer in three.js: the per-texel PRT_transfer primitives of `prt bake MESH
// --lightmap WxH --gltf OUT.glb` (docs/formats.md, "The engine glTF", "Per texel": the root's CPCA model
// and, on the primitive, {model, texCoord, width, height, cluster, weights}; `cluster` a KTX2 RGBA16F 2D
// texture of R = cluster k, G = coverage code (0 empty, 1 covered, 2 gutter); `weights` a KTX2 RGBA16F
// array of ceil(N / 4) layers, w_{4a+1..4a+4} in layer a), shaded per pixel as `prt render` shades the
// decompressed lightmap (docs/conventions.md, "Lightmap rendering"): each texel's radiance
// s_k0 + sum_j w_j s_kj and prt's coverage-aware mip chain of it are rebuilt on the GPU when the lighting
// changes (prt_lightmap_mips.js, LightmapRadiance), the pixel samples that chain trilinearly at its
// lightmap UV (clamp to edge) and adds the discs' direct light with the bake's albedo (_PRT_ALBEDO per
// vertex, interpolated).
import { ClampToEdgeWrapping, Color, DataArrayTexture, HalfFloatType, NearestFilter, RGBAFormat, ShaderMaterial, UniformsUtils } from 'three';
import { SUN_GLSL, SURFACE_VERTEX_GLSL } from './prt_sun.js';

const VK_FORMAT_R16G16B16A16_SFLOAT = 97;

/// A KTX2 file of RGBA16F texels (one level, no supercompression, W x H x layers; a 2D texture as one
/// layer) as a DataArrayTexture read with texelFetch (nearest, rows top first as the file stores them and
/// as glTF UVs address them). Throws naming `what`.
export function parseKtx2(buffer, what) {
  const bytes = new Uint8Array(buffer);
  const identifier = [0xab, 0x4b, 0x54, 0x58, 0x20, 0x32, 0x30, 0xbb, 0x0d, 0x0a, 0x1a, 0x0a];
  if (bytes.length < 104 || identifier.some((b, i) => bytes[i] !== b)) throw new Error(`${what}: not a KTX2 file`);
  const view = new DataView(buffer);
  const u32 = (o) => view.getUint32(o, true);
  const [format, width, height, layers, levels, scheme] = [u32(12), u32(20), u32(24), Math.max(1, u32(32)), u32(40), u32(44)];
  if (format !== VK_FORMAT_R16G16B16A16_SFLOAT || scheme !== 0 || levels > 1 || u32(28) > 1) {
    throw new Error(`${what}: KTX2 format ${format}, supercompression ${scheme}, ${levels} levels, depth ${u32(28)} (expected R16G16B16A16_SFLOAT, none, 1, 2D)`);
  }
  const offset = Number(view.getBigUint64(80, true)), length = Number(view.getBigUint64(88, true));
  if (length !== width * height * layers * 8 || offset + length > bytes.length) throw new Error(`${what}: KTX2 level 0 holds ${length} bytes`);
  const texture = new DataArrayTexture(new Uint16Array(buffer.slice(offset, offset + length)), width, height, layers);
  texture.format = RGBAFormat;
  texture.type = HalfFloatType;
  texture.minFilter = texture.magFilter = NearestFilter;
  texture.wrapS = texture.wrapT = ClampToEdgeWrapping;
  texture.generateMipmaps = false;
  texture.flipY = false;
  texture.needsUpdate = true;
  return texture;
}

/// Loads a primitive's per-texel PRT_transfer textures through the GLTFLoader parser. model: the root
/// model it names (prt_transfer.js, loadModel). Throws naming `what` for a malformed extension.
export async function loadLightmap(parser, ext, model, what) {
  const image = async (index) => {
    const def = parser.json.images && parser.json.images[index];
    if (!def || def.mimeType !== 'image/ktx2' || def.bufferView === undefined) throw new Error(`${what}: image ${index} is not an embedded KTX2 image`);
    return parseKtx2(await parser.getDependency('bufferView', def.bufferView), `${what} image ${index}`);
  };
  if (!(Number.isInteger(ext.width) && ext.width >= 1 && Number.isInteger(ext.height) && ext.height >= 1)) {
    throw new Error(`${what}: width ${ext.width} or height ${ext.height} is not a positive integer`);
  }
  const layers = Math.ceil(model.terms / 4);
  if (layers > 0 && ext.weights === undefined) throw new Error(`${what}: no weights image for ${model.terms} terms`);
  const [cluster, weights] = await Promise.all([image(ext.cluster), layers > 0 ? image(ext.weights) : null]);
  const size = (t) => `${t.image.width}x${t.image.height}x${t.image.depth}`;
  if (cluster.image.width !== ext.width || cluster.image.height !== ext.height || cluster.image.depth !== 1) {
    throw new Error(`${what}: its cluster texture is ${size(cluster)}, the extension says ${ext.width}x${ext.height}`);
  }
  if (weights && (weights.image.width !== ext.width || weights.image.height !== ext.height || weights.image.depth !== layers)) {
    throw new Error(`${what}: its weights texture is ${size(weights)}, the extension says ${ext.width}x${ext.height}x${layers}`);
  }
  return { model: ext.model, texCoord: ext.texCoord || 0, width: ext.width, height: ext.height, layers, cluster, weights };
}

const VERTEX = /* glsl */ `
#if defined(PRT_UV1) && !defined(USE_UV1)
in vec2 uv1;
#endif
out vec2 prt_lightmap_uv;
#ifdef PRT_VERTEX_ALBEDO
in vec3 _prt_albedo;
out vec3 prt_vertex_albedo;
#endif
${SURFACE_VERTEX_GLSL}
void main() {
  prt_lightmap_uv = PRT_LIGHTMAP_UV;
#ifdef PRT_VERTEX_ALBEDO
  prt_vertex_albedo = _prt_albedo;
#endif
  gl_Position = prt_surface();
}`;

const FRAGMENT = /* glsl */ `
${SUN_GLSL}
uniform sampler2D prt_radiance;  // LightmapRadiance: the radiance per texel and its mip chain
uniform vec3 prt_albedo;
in vec2 prt_lightmap_uv;
#ifdef PRT_VERTEX_ALBEDO
in vec3 prt_vertex_albedo;  // the bake's albedo (_PRT_ALBEDO), interpolated as prt render interpolates it
#define PRT_DIRECT_ALBEDO prt_vertex_albedo
#else
#define PRT_DIRECT_ALBEDO prt_albedo
#endif
in vec3 prt_world_position;
in vec3 prt_world_normal;

void main() {
  // Trilinear over the coverage-aware mip chain, clamp to edge, as prt render samples its lightmap.
  vec2 uv = prt_lightmap_uv;
  if (any(isnan(uv)) || any(isinf(uv))) uv = vec2(0.0);
  vec3 radiance = texture(prt_radiance, uv).rgb;
  if (disc_count > 0) {
    radiance = max(radiance + PRT_DIRECT_ALBEDO * 0.31830988618379067 * prt_disc_light(prt_world_position, normalize(prt_world_normal)), vec3(0.0));
  }
  gl_FragColor = vec4(radiance, 1.0);
  #include <tonemapping_fragment>
  #include <colorspace_fragment>
}`;

/// The lightmap material of `mesh` (mesh.userData.prtLightmap from the plugin) of `model` drawing
/// `radiance` (its LightmapRadiance, rebuilt by PrtRelighting when the lighting changes). The discs' direct light takes the
/// bake's albedo, the primitive's _PRT_ALBEDO interpolated (as prt render does); a file without it (an
/// older export) falls back to the old material's colour (set it to the bake's albedo).
export function createLightmapMaterial(mesh, lightmap, model, radiance, sun) {
  const uv1 = lightmap.texCoord === 1;
  const vertexAlbedo = !!mesh.geometry.attributes._prt_albedo;
  const material = new ShaderMaterial({
    defines: { PRT_LIGHTMAP_UV: uv1 ? 'uv1' : 'uv', ...(uv1 ? { PRT_UV1: '' } : {}), ...(vertexAlbedo ? { PRT_VERTEX_ALBEDO: '' } : {}) },
    uniforms: UniformsUtils.merge([{ prt_albedo: { value: new Color(1, 1, 1).copy(mesh.material.color || new Color(1, 1, 1)) },
                                     disc_shadows: { value: model.kind !== 'unshadowed' } }]),
    vertexShader: VERTEX,
    fragmentShader: FRAGMENT,
  });
  // Shared, not copied: the discs change every frame for every material.
  Object.assign(material.uniforms, sun.uniforms, { prt_radiance: { value: radiance.texture } });
  material.name = `prt-lightmap:${mesh.material.name || ''}`;
  material.side = mesh.material.side;
  return material;
}
