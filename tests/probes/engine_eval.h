#pragma once
// Re-implementations of each target engine's OWN evaluation of what it stores per probe, written from
// the engines' source (paths cited per function), independent of prt's encoders in
// src/probes/engine_sh.h. Each returns the diffuse lighting factor the engine multiplies the albedo by,
// which for a Lambert surface is E(n)/pi.
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <glm/vec3.hpp>

namespace prt::test {

using Rgb = glm::dvec3;

/// three.js: src/math/SphericalHarmonics3.js getIrradianceAt (the same constants as
/// src/renderers/shaders/ShaderChunk/lights_pars_begin.glsl.js shGetIrradianceAt), then
/// BRDF_Lambert (src/renderers/shaders/ShaderChunk/bsdfs.glsl.js: RECIPROCAL_PI * diffuseColor) in
/// lights_lambert_pars_fragment / RE_IndirectDiffuse. `sh` is LightProbe JSON "sh" (27 floats,
/// coefficient-major r,g,b); the probe's intensity (1) scales it in WebGLLights.
inline Rgb threejs_diffuse(const std::vector<float>& sh, const Rgb& n) {
  auto c = [&](int i) { return Rgb(sh[3 * i], sh[3 * i + 1], sh[3 * i + 2]); };
  const double x = n.x, y = n.y, z = n.z;
  Rgb t = c(0) * 0.886227;
  t += c(1) * (2.0 * 0.511664 * y);
  t += c(2) * (2.0 * 0.511664 * z);
  t += c(3) * (2.0 * 0.511664 * x);
  t += c(4) * (2.0 * 0.429043 * x * y);
  t += c(5) * (2.0 * 0.429043 * y * z);
  t += c(6) * (0.743125 * z * z - 0.247708);
  t += c(7) * (2.0 * 0.429043 * x * z);
  t += c(8) * (0.429043 * (x * x - y * y));
  return t * (1.0 / 3.14159265358979323846);  // RECIPROCAL_PI
}

/// Unity: CGIncludes/UnityCG.cginc ShadeSH9 = SHEvalLinearL0L1 + SHEvalLinearL2 with
/// normal.w = 1, vB = normal.xyzz * normal.yzzx, vC = x^2 - y^2, and the packing of
/// SphericalHarmonicsL2 u[channel*9+i] into unity_SHAr/g/b = (u3, u1, u2, u0 - u6),
/// unity_SHBr/g/b = (u4, u5, 3 u6, u7), unity_SHC = (u8_r, u8_g, u8_b) (Unity's
/// SphericalHarmonicsL2 -> shader constants conversion, as in the Scriptable Render Pipeline Core
/// package's SphericalHarmonics.cs GetShaderConstantsFromNormalizedSH). `n` is a Unity-frame normal.
inline Rgb unity_shade_sh9(const std::vector<float>& u, const Rgb& n) {
  Rgb out;
  for (int ch = 0; ch < 3; ++ch) {
    const float* s = u.data() + 9 * ch;
    const double sha[4] = {s[3], s[1], s[2], s[0] - s[6]};
    const double shb[4] = {s[4], s[5], 3.0 * s[6], s[7]};
    const double normal[4] = {n.x, n.y, n.z, 1.0};
    double l0l1 = 0.0;
    for (int k = 0; k < 4; ++k) l0l1 += sha[k] * normal[k];
    const double vb[4] = {n.x * n.y, n.y * n.z, n.z * n.z, n.z * n.x};
    double l2 = 0.0;
    for (int k = 0; k < 4; ++k) l2 += shb[k] * vb[k];
    l2 += s[8] * (n.x * n.x - n.y * n.y);
    out[ch] = l0l1 + l2;
  }
  return out;
}

/// Godot 4: servers/rendering/renderer_rd/shaders/forward_clustered/scene_forward_clustered.glsl,
/// lightmap capture branch (INSTANCE_FLAGS_USE_LIGHTMAP_CAPTURE): the Ramamoorthi-Hanrahan formula with
/// c1..c5 on lightmap_captures.data[index].sh[0..8] (the probe_data "sh" Colors, interpolated); the
/// result goes into ambient_light, which is multiplied by the albedo. `sh` is 9 Colors as 27 floats.
inline Rgb godot_ambient(const std::vector<float>& sh, const Rgb& w) {
  auto s = [&](int i) { return Rgb(sh[3 * i], sh[3 * i + 1], sh[3 * i + 2]); };
  const double c1 = 0.429043, c2 = 0.511664, c3 = 0.743125, c4 = 0.886227, c5 = 0.247708;
  return c1 * s(8) * (w.x * w.x - w.y * w.y) + c3 * s(6) * w.z * w.z + c4 * s(0) - c5 * s(6) +
         2.0 * c1 * s(4) * w.x * w.y + 2.0 * c1 * s(7) * w.x * w.z + 2.0 * c1 * s(5) * w.y * w.z +
         2.0 * c2 * s(3) * w.x + 2.0 * c2 * s(1) * w.y + 2.0 * c2 * s(2) * w.z;
}

/// Filament: shaders/src/light_indirect.fs Irradiance_SphericalHarmonics (3 bands, iblSH from
/// IndirectLight::irradiance(3, sh) or cmgen's sh.txt), max(..., 0); the diffuse IBL term is
/// diffuseColor * irradiance (the 1/pi is pre-scaled into the coefficients).
inline Rgb filament_irradiance(const std::array<Rgb, 9>& sh, const Rgb& n) {
  const Rgb r = sh[0] + sh[1] * n.y + sh[2] * n.z + sh[3] * n.x + sh[4] * (n.y * n.x) + sh[5] * (n.y * n.z) +
                sh[6] * (3.0 * n.z * n.z - 1.0) + sh[7] * (n.z * n.x) + sh[8] * (n.x * n.x - n.y * n.y);
  return glm::max(r, Rgb(0.0));
}

/// Babylon.js: loaders/src/glTF/2.0/Extensions/EXT_lights_image_based.ts (SphericalHarmonics.FromArray
/// of irradianceCoefficients, scaleInPlace(intensity), convertIrradianceToLambertianRadiance = scale by
/// 1/pi), core/src/Maths/sphericalPolynomial.ts (preScaleForRendering: times SH3ylmBasisConstants
/// = [sqrt(1/4pi), -sqrt(3/4pi), sqrt(3/4pi), -sqrt(3/4pi), sqrt(15/4pi), -sqrt(15/4pi), sqrt(5/16pi),
/// -sqrt(15/4pi), sqrt(15/16pi)], the polynomial's preScaledHarmonics), and
/// core/src/Shaders/ShadersInclude/harmonicsFunctions.fx computeEnvironmentIrradiance (SPHERICAL_HARMONICS):
/// L00 + L1_1 y + L10 z + L11 x + L2_2 yx + L2_1 yz + L20 (3z^2 - 1) + L21 zx + L22 (x^2 - y^2).
inline Rgb babylon_irradiance(const std::array<Rgb, 9>& coefficients, double intensity, const Rgb& n) {
  const double pi = 3.14159265358979323846;
  const double k[9] = {std::sqrt(1 / (4 * pi)), -std::sqrt(3 / (4 * pi)), std::sqrt(3 / (4 * pi)), -std::sqrt(3 / (4 * pi)),
                       std::sqrt(15 / (4 * pi)), -std::sqrt(15 / (4 * pi)), std::sqrt(5 / (16 * pi)), -std::sqrt(15 / (4 * pi)),
                       std::sqrt(15 / (16 * pi))};
  std::array<Rgb, 9> l;
  for (int i = 0; i < 9; ++i) l[i] = coefficients[i] * intensity * (1.0 / pi) * k[i];
  return l[0] + l[1] * n.y + l[2] * n.z + l[3] * n.x + l[4] * (n.y * n.x) + l[5] * (n.y * n.z) +
         l[6] * (3.0 * n.z * n.z - 1.0) + l[7] * (n.z * n.x) + l[8] * (n.x * n.x - n.y * n.y);
}

/// Bevy: crates/bevy_pbr/src/light_probe/irradiance_volume.wgsl irradiance_volume_light: with
/// resolution = dims / (1, 2, 3), stp = clamp((unit_pos + 0.5) * resolution, 0.5, resolution - 0.5),
/// uvw = stp / dims, neg_offset = select(0, 0.5, N < 0) added to uvw.y, slices +0, +1/3, +2/3 in w for
/// the X, Y, Z cubes, trilinear textureSampleLevel (clamp-to-edge, linear), then
/// rgb_x NN.x + rgb_y NN.y + rgb_z NN.z (times the volume's intensity, 1 here).
/// `rgba` holds the texels x fastest; `unit_pos` is the position in the volume's unit cube [-0.5, 0.5]^3.
inline Rgb bevy_irradiance(const std::vector<float>& rgba, int width, int height, int depth, const Rgb& unit_pos, const Rgb& normal) {
  const Rgb dims(width, height, depth);
  const Rgb resolution = dims / Rgb(1, 2, 3);
  const Rgb stp = glm::clamp((unit_pos + 0.5) * resolution, Rgb(0.5), resolution - Rgb(0.5));
  const Rgb uvw = stp / dims;
  auto texel = [&](int x, int y, int z) {
    x = std::clamp(x, 0, width - 1), y = std::clamp(y, 0, height - 1), z = std::clamp(z, 0, depth - 1);
    const float* t = rgba.data() + 4 * ((static_cast<std::size_t>(z) * height + y) * width + x);
    return Rgb(t[0], t[1], t[2]);
  };
  auto sample = [&](const Rgb& coord) {  // WebGPU linear filtering at normalised coordinates
    const Rgb p = coord * dims - 0.5;
    const Rgb f = glm::floor(p), t = p - f;
    Rgb sum(0.0);
    for (int dz = 0; dz < 2; ++dz)
      for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx) {
          const double w = (dx ? t.x : 1 - t.x) * (dy ? t.y : 1 - t.y) * (dz ? t.z : 1 - t.z);
          sum += w * texel(static_cast<int>(f.x) + dx, static_cast<int>(f.y) + dy, static_cast<int>(f.z) + dz);
        }
    return sum;
  };
  const Rgb neg(normal.x < 0 ? 0.5 : 0.0, normal.y < 0 ? 0.5 : 0.0, normal.z < 0 ? 0.5 : 0.0);
  const Rgb rgb_x = sample(uvw + Rgb(0.0, neg.x, 0.0));
  const Rgb rgb_y = sample(uvw + Rgb(0.0, neg.y, 1.0 / 3.0));
  const Rgb rgb_z = sample(uvw + Rgb(0.0, neg.z, 2.0 / 3.0));
  const Rgb nn = normal * normal;
  return rgb_x * nn.x + rgb_y * nn.y + rgb_z * nn.z;
}

}  // namespace prt::test
