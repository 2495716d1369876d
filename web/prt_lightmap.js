// Per-texel (lightmap) transfer in three.js: the PRT_lightmap_transfer primitives of `prt bake MESH
// --lightmap WxH --gltf OUT.glb` (docs/formats.md, "Lightmap transfer in glTF": KTX2 RGBA16F texture
// arrays, value 4k+j of a texel's block in component j of layer k, channel-major then SH index; image
// `transfer` and, for interreflected bakes, `bounceOnly`), shaded per pixel as `prt render` shades a
// lightmap (docs/conventions.md, "Lightmap rendering"): every layer sampled bilinearly at the lightmap UV
// (level 0 only: this runtime builds no mip chain, so a lightmap seen minified aliases where prt's
// coverage-aware mips would not), dotted with the rotated sky (and the bounce layers with the discs'
// SH), plus the discs' direct light with the material's base colour as albedo.
import { ClampToEdgeWrapping, Color, DataArrayTexture, HalfFloatType, LinearFilter, RGBAFormat, ShaderMaterial, UniformsUtils, Vector4 } from 'three';
import { SUN_GLSL, SURFACE_VERTEX_GLSL } from './prt_sun.js';

const VK_FORMAT_R16G16B16A16_SFLOAT = 97;

/// A KTX2 file of RGBA16F texels (one level, no supercompression, W x H x layers) as a DataArrayTexture
/// (rows top first, as the file stores them and as glTF UVs address them). Throws naming `what`.
export function parseKtx2(buffer, what) {
  const bytes = new Uint8Array(buffer);
  const identifier = [0xab, 0x4b, 0x54, 0x58, 0x20, 0x32, 0x30, 0xbb, 0x0d, 0x0a, 0x1a, 0x0a];
  if (bytes.length < 104 || identifier.some((b, i) => bytes[i] !== b)) throw new Error(`${what}: not a KTX2 file`);
  const view = new DataView(buffer);
  const u32 = (o) => view.getUint32(o, true);
  const [format, width, height, layers, levels, scheme] = [u32(12), u32(20), u32(24), Math.max(1, u32(32)), u32(40), u32(44)];
  if (format !== VK_FORMAT_R16G16B16A16_SFLOAT || scheme !== 0 || levels > 1) {
    throw new Error(`${what}: KTX2 format ${format}, supercompression ${scheme}, ${levels} levels (expected R16G16B16A16_SFLOAT, none, 1)`);
  }
  const offset = Number(view.getBigUint64(80, true)), length = Number(view.getBigUint64(88, true));
  if (length !== width * height * layers * 8 || offset + length > bytes.length) throw new Error(`${what}: KTX2 level 0 holds ${length} bytes`);
  const texture = new DataArrayTexture(new Uint16Array(buffer.slice(offset, offset + length)), width, height, layers);
  texture.format = RGBAFormat;
  texture.type = HalfFloatType;
  texture.minFilter = texture.magFilter = LinearFilter;
  texture.wrapS = texture.wrapT = ClampToEdgeWrapping;
  texture.generateMipmaps = false;
  texture.flipY = false;
  texture.needsUpdate = true;
  return texture;
}

/// Loads a primitive's PRT_lightmap_transfer textures through the GLTFLoader parser.
export async function loadLightmap(parser, ext, what) {
  const image = async (index) => {
    const def = parser.json.images[index];
    if (!def || def.mimeType !== 'image/ktx2' || def.bufferView === undefined) throw new Error(`${what}: image ${index} is not an embedded KTX2 image`);
    return parseKtx2(await parser.getDependency('bufferView', def.bufferView), `${what} image ${index}`);
  };
  const transfer = await image(ext.transfer);
  const bounce = ext.bounceOnly !== undefined ? await image(ext.bounceOnly) : null;
  const layers = Math.ceil(ext.channels * ext.bands * ext.bands / 4);
  if (transfer.image.depth !== layers || transfer.image.width !== ext.width || transfer.image.height !== ext.height) {
    throw new Error(`${what}: its texture is ${transfer.image.width}x${transfer.image.height}x${transfer.image.depth}, the extension says ${ext.width}x${ext.height}x${layers}`);
  }
  return { bands: ext.bands, channels: ext.channels, kind: ext.kind, texCoord: ext.texCoord || 0, layers, transfer, bounce };
}

/// Per-layer weights that turn a texel's layers into RGB: channel c = sum_k dot(layer_k, w[c][k]).
/// light: RGB SH (coefficient-major) with at least `bands` bands. Writes into out (3 arrays of Vector4).
export function layerWeights(lightmap, light, out) {
  const n2 = lightmap.bands * lightmap.bands;
  for (let k = 0; k < lightmap.layers; k++) {
    for (let c = 0; c < 3; c++) out[c][k].set(0, 0, 0, 0);
    for (let j = 0; j < 4; j++) {
      const v = 4 * k + j;
      if (v >= lightmap.channels * n2) break;
      const i = v % n2;
      const channels = lightmap.channels === 1 ? [0, 1, 2] : [Math.floor(v / n2)];
      for (const c of channels) out[c][k].setComponent(j, light ? light[3 * i + c] : 0);
    }
  }
}

const VERTEX = /* glsl */ `
#if defined(PRT_UV1) && !defined(USE_UV1)
in vec2 uv1;
#endif
out vec2 prt_lightmap_uv;
${SURFACE_VERTEX_GLSL}
void main() {
  prt_lightmap_uv = PRT_LIGHTMAP_UV;
  gl_Position = prt_surface();
}`;

const FRAGMENT = /* glsl */ `
precision highp sampler2DArray;
${SUN_GLSL}
uniform sampler2DArray prt_transfer;
uniform vec4 prt_sky_r[LAYERS], prt_sky_g[LAYERS], prt_sky_b[LAYERS];
#ifdef PRT_BOUNCE
uniform sampler2DArray prt_bounce;
uniform vec4 prt_disc_r[LAYERS], prt_disc_g[LAYERS], prt_disc_b[LAYERS];
#endif
uniform vec3 prt_albedo;
in vec2 prt_lightmap_uv;
in vec3 prt_world_position;
in vec3 prt_world_normal;
void main() {
  vec3 radiance = vec3(0.0);
  for (int k = 0; k < LAYERS; ++k) {
    vec4 t = texture(prt_transfer, vec3(prt_lightmap_uv, float(k)));
    radiance += vec3(dot(t, prt_sky_r[k]), dot(t, prt_sky_g[k]), dot(t, prt_sky_b[k]));
#ifdef PRT_BOUNCE
    vec4 b = texture(prt_bounce, vec3(prt_lightmap_uv, float(k)));
    radiance += vec3(dot(b, prt_disc_r[k]), dot(b, prt_disc_g[k]), dot(b, prt_disc_b[k]));
#endif
  }
  if (prt_disc_count > 0) {
    radiance = max(radiance + prt_albedo * 0.31830988618379067 * prt_disc_light(prt_world_position, normalize(prt_world_normal)), vec3(0.0));
  }
  gl_FragColor = vec4(radiance, 1.0);
  #include <tonemapping_fragment>
  #include <colorspace_fragment>
}`;

/// The lightmap material of `mesh` (mesh.userData.prtLightmap from the plugin). The discs' direct light
/// takes the old material's colour as albedo (prt: the mesh's albedo; set it to the bake's).
export function createLightmapMaterial(mesh, lightmap, sun) {
  const weights = () => Array.from({ length: lightmap.layers }, () => new Vector4());
  const material = new ShaderMaterial({
    defines: { LAYERS: lightmap.layers, PRT_LIGHTMAP_UV: lightmap.texCoord === 1 ? 'uv1' : 'uv', ...(lightmap.texCoord === 1 ? { PRT_UV1: '' } : {}),
               ...(lightmap.bounce ? { PRT_BOUNCE: '' } : {}) },
    uniforms: UniformsUtils.merge([{ prt_albedo: { value: new Color(1, 1, 1).copy(mesh.material.color || new Color(1, 1, 1)) },
                                     prt_disc_shadows: { value: lightmap.kind !== 'unshadowed' } }]),
    vertexShader: VERTEX,
    fragmentShader: FRAGMENT,
  });
  Object.assign(material.uniforms, sun.uniforms, {
    prt_transfer: { value: lightmap.transfer }, prt_bounce: { value: lightmap.bounce },
    prt_sky_r: { value: weights() }, prt_sky_g: { value: weights() }, prt_sky_b: { value: weights() },
    prt_disc_r: { value: weights() }, prt_disc_g: { value: weights() }, prt_disc_b: { value: weights() },
  });
  material.name = `prt-lightmap:${mesh.material.name || ''}`;
  return material;
}

/// Sets a lightmap material's weights for this frame's sky and discs' SH (null: none).
export function updateLightmapMaterial(material, lightmap, sky, discs) {
  const u = material.uniforms;
  layerWeights(lightmap, sky, [u.prt_sky_r.value, u.prt_sky_g.value, u.prt_sky_b.value]);
  layerWeights(lightmap, discs, [u.prt_disc_r.value, u.prt_disc_g.value, u.prt_disc_b.value]);
}
