// The glTF export (EXT_lights_image_based) as Babylon.js reads it: Babylon's own glTF loader in a
// NullEngine builds the scene and the environment texture (its SphericalHarmonics / SphericalPolynomial
// from irradianceCoefficients, its reflection matrix), Babylon's PBRMaterial decides the shader
// defines, and Babylon's own shader code (pbr.vertex's irradiance lines and harmonicsFunctions'
// computeEnvironmentIrradiance, compiled to JS per channel) evaluates the diffuse irradiance at every
// test direction. Checked against prt's E/pi (engine_fixture's truth.json):
//  1. default (left-handed) scene: E(n)/pi at the glTF normal n, axis and random directions, both HDRIs;
//  2. right-handed scene (scene.useRightHandedSystem): E(Ry(180) n)/pi, what the README documents;
//  3. the specular cube as Babylon holds it (the loader's image bytes, decoded, RGBD-decoded, rows flipped
//     as Babylon's upload does) through Babylon's own CubeMapToSphericalPolynomialTools gives the same
//     irradiance as the file's coefficients (a mirrored or row-flipped cube disagrees by tens of %);
//  4. under the constant environment (3, 1.5, 0.75) every texel is (255, 186, 136, 85) and decodes to it.
// Re-implemented here (no GPU): the GPU upload (rows flipped, Babylon's UNPACK_FLIP_Y for RGBD cubes)
// and the RGBD decode pow(rgb, 2.2) / a (helperFunctions' fromRGBD; the 2.2 is checked in the source).
// Usage: node test_babylon.mjs --work DIR (the engines_fixture output)
import { createRequire } from 'node:module';
import { join } from 'node:path';
import { Checker, argument, decodePng, fixtureFolders, glslFunction } from './common.mjs';

const require = createRequire(import.meta.url);
const BABYLON = require('babylonjs');
require('babylonjs-loaders');
BABYLON.Logger.LogLevels = BABYLON.Logger.ErrorLogLevel;
const { readFileSync } = await import('node:fs');

const work = argument('work');
const check = new Checker('engines_babylon');

// The GPU side of the environment texture, which a NullEngine does not have: keep what the loader
// hands to the upload (the images and the spherical polynomial) instead of uploading it.
function nullEngine() {
  const engine = new BABYLON.NullEngine();
  engine.createRawCubeTexture = function (data, size) {
    const t = new BABYLON.InternalTexture(this, BABYLON.InternalTextureSource.CubeRaw);
    t.isCube = true;
    t.width = t.height = t.baseWidth = t.baseHeight = size;
    t.isReady = true;
    return t;
  };
  BABYLON.RawCubeTexture.prototype.updateRGBDAsync = async function (data, sphericalPolynomial) {
    this.prtImages = data;
    this._texture._sphericalPolynomial = sphericalPolynomial;
  };
  return engine;
}

// Babylon's shader code for the vertex-stage irradiance, checked to be what this test evaluates.
const vertex = BABYLON.ShaderStore.ShadersStore.pbrVertexShader;
for (const line of ['vec3 reflectionVector=vec3(reflectionMatrix*vec4(vNormalW,0)).xyz;',
                    '#ifdef REFLECTIONMAP_OPPOSITEZ\nreflectionVector.z*=-1.0;\n#endif\nvEnvironmentIrradiance=computeEnvironmentIrradiance(reflectionVector);'])
  check.check('pbr.vertex computes the irradiance as this test models it', vertex.includes(line), JSON.stringify(line));
const harmonicsSource = BABYLON.ShaderStore.IncludesShadersStore.harmonicsFunctions;
const harmonicsBlock = harmonicsSource.slice(harmonicsSource.indexOf('#ifdef SPHERICAL_HARMONICS'), harmonicsSource.indexOf('#else'));
const uniforms = ['vSphericalL00', 'vSphericalL1_1', 'vSphericalL10', 'vSphericalL11', 'vSphericalL2_2', 'vSphericalL2_1', 'vSphericalL20', 'vSphericalL21', 'vSphericalL22'];
const computeEnvironmentIrradiance = glslFunction(harmonicsBlock, 'computeEnvironmentIrradiance', 'normal', uniforms);
const helpers = BABYLON.ShaderStore.IncludesShadersStore.helperFunctions;
check.check('Babylon decodes RGBD with pow(rgb, 2.2) / a', helpers.includes('const float LinearEncodePowerApprox=2.2;') &&
            helpers.includes('vec3 fromRGBD(vec4 rgbd) {rgbd.rgb=toLinearSpace(rgbd.rgb);return rgbd.rgb/rgbd.a;}'));

async function load(file, rightHanded) {
  const scene = new BABYLON.Scene(nullEngine());
  scene.useRightHandedSystem = rightHanded;
  const result = await BABYLON.ImportMeshAsync(new Uint8Array(readFileSync(file)), scene, { pluginExtension: '.glb' });
  const mesh = result.meshes.find((m) => m.getTotalVertices() > 0);
  mesh.computeWorldMatrix(true);
  mesh.material.isReadyForSubMesh(mesh, mesh.subMeshes[0]);
  const defines = mesh.subMeshes[0].materialDefines;
  for (const d of ['REFLECTION', 'USESPHERICALFROMREFLECTIONMAP', 'SPHERICAL_HARMONICS', 'USESPHERICALINVERTEX'])
    check.check(`${file}: PBR define ${d}`, defines[d] === true);
  check.check(`${file}: no INVERTCUBICMAP`, !defines.INVERTCUBICMAP);
  return { scene, texture: scene.environmentTexture, mesh, defines };
}

// Babylon's irradiance for a vertex with glTF normal n: the mesh's world matrix (the loader's root
// conversion), the texture's reflection matrix, the OPPOSITEZ define, computeEnvironmentIrradiance.
function irradiance(loaded, n, polynomial = loaded.texture.sphericalPolynomial) {
  const world = BABYLON.Vector3.TransformNormal(new BABYLON.Vector3(...n), loaded.mesh.getWorldMatrix()).normalize();
  const r = BABYLON.Vector3.TransformNormal(world, loaded.texture.getReflectionTextureMatrix());
  if (loaded.defines.REFLECTIONMAP_OPPOSITEZ) r.z *= -1;
  const h = polynomial.preScaledHarmonics;
  const inputs = {};
  ['l00', 'l1_1', 'l10', 'l11', 'l2_2', 'l2_1', 'l20', 'l21', 'l22'].forEach((k, i) => { inputs[uniforms[i]] = [h[k].x, h[k].y, h[k].z]; });
  return computeEnvironmentIrradiance([r.x, r.y, r.z], inputs);
}

// The faces as Babylon holds them on the GPU (GL row order: the PNG rows flipped), RGBD-decoded.
function gpuFaces(texture) {
  const size = texture.getSize().width;
  return texture.prtImages[0].map((bytes) => {
    const png = decodePng(Buffer.from(bytes.buffer, bytes.byteOffset, bytes.byteLength));
    const out = new Float32Array(size * size * 4);
    for (let y = 0; y < size; y++)
      for (let x = 0; x < size; x++) {
        const from = 4 * ((size - 1 - y) * size + x), to = 4 * (y * size + x), a = png.pixels[from + 3] / 255;
        for (let k = 0; k < 3; k++) out[to + k] = Math.pow(png.pixels[from + k] / 255, 2.2) / a;
        out[to + 3] = 1;
      }
    return out;
  });
}

const axes = (d) => Math.abs(d[0]) + Math.abs(d[1]) + Math.abs(d[2]) === 1;
for (const { name, dir, truth } of fixtureFolders(work)) {
  const file = join(dir, 'gltf.glb');
  const scale = check.scaleOf(truth.sky);
  const left = await load(file, false);
  truth.directions.forEach((d, k) => check.close(`${name} left-handed n=${d}`, irradiance(left, d), truth.sky[k], scale, 1e-4));
  const right = await load(file, true);
  truth.directions.forEach((d, k) => {
    if (!axes(d)) return;
    const turned = truth.directions.findIndex((e) => e[0] === -d[0] && e[1] === d[1] && e[2] === -d[2]);
    check.close(`${name} right-handed n=${d} shows E(Ry(180) n)`, irradiance(right, d), truth.sky[turned], scale, 1e-4);
  });
}

// 3. The cube Babylon samples against the coefficients it uses, on a smooth (3-band) environment where
// a 32-pixel cube resolves the lighting: Babylon's own cube-to-SH must give the same irradiance.
{
  const smooth = await load(join(work, 'smooth', 'gltf.glb'), false);
  const size = smooth.texture.getSize().width;
  const [right, left, up, down, front, back] = gpuFaces(smooth.texture);
  const fromCube = BABYLON.CubeMapToSphericalPolynomialTools.ConvertCubeMapToSphericalPolynomial({
    size, right, left, up, down, front, back, format: BABYLON.Constants.TEXTUREFORMAT_RGBA,
    type: BABYLON.Constants.TEXTURETYPE_FLOAT, gammaSpace: false });
  const truth = JSON.parse(readFileSync(join(work, 'smooth', 'truth.json'), 'utf8'));
  const scale = check.scaleOf(truth.sky);
  truth.directions.forEach((d) =>
    check.close(`smooth: Babylon's cube-to-SH of the specular faces vs the file's SH at n=${d}`,
                irradiance(smooth, d, fromCube), irradiance(smooth, d), scale, 0.01));
}

// 4. Constant environment: RGBD bytes and their decoded value in every texel of every face and level.
{
  const constant = await load(join(work, 'constant', 'gltf.glb'), false);
  let wrong = 0, first = '';
  constant.texture.prtImages.forEach((level, mip) => level.forEach((bytes, face) => {
    const png = decodePng(Buffer.from(bytes.buffer, bytes.byteOffset, bytes.byteLength));
    for (let i = 0; i < png.width * png.height; i++) {
      const p = png.pixels.subarray(4 * i, 4 * i + 4);
      if (p[0] !== 255 || p[1] !== 186 || p[2] !== 136 || p[3] !== 85) {
        if (!wrong++) first = `mip ${mip} face ${face} texel ${i}: (${p.join(', ')})`;
      }
    }
  }));
  check.check('constant (3, 1.5, 0.75): every specular texel is RGBD (255, 186, 136, 85)', wrong === 0, `${wrong} texels differ, first ${first}`);
  const decoded = [255, 186, 136].map((v) => Math.pow(v / 255, 2.2) / (85 / 255));
  check.close('constant: decoded texel', decoded, [3, 1.5, 0.75], 3, 0.01);
}
check.finish();
