#pragma once
// Isotropic BRDFs for glossy PRT: definitions, evaluation and the SPEC strings / material files that
// select them.
//
// FRAME. A BRDF is evaluated in a LOCAL frame whose +z is the surface normal (frame.h says how a mesh
// vertex's local frame is built). Directions w_i (toward the light) and w_o (toward the viewer) are
// unit vectors pointing AWAY from the surface. Every BRDF here is isotropic: f depends only on
// theta_i, theta_o and phi_o - phi_i, and is symmetric under phi -> -phi.
//
// DEFINITIONS (f in 1/sr; "weight" is the lobe's RGB factor, each component in [0, 1]):
//   lambert      f = albedo / pi
//   phong        f = ks (n + 2) / (2 pi) max(r . w_o, 0)^n,     r = (-w_i.x, -w_i.y, w_i.z) (mirror of w_i)
//                (normalized: at normal incidence the directional albedo is exactly ks)
//   blinn-phong  f = ks (n + 8) / (8 pi) (n_z . h)^n,           h = normalize(w_i + w_o)
//                (the approximately energy-normalized form of Akenine-Moller et al., Real-Time
//                Rendering: the (n + 8) / (8 pi) factor, not (n + 2) / (2 pi), which normalizes the
//                half-vector distribution but not the reflected lobe)
//   ggx          f = D(h) V(w_i, w_o) F(w_i . h), alpha = roughness^2 (the glTF / Disney convention),
//                D = alpha^2 / (pi ((h.z)^2 (alpha^2 - 1) + 1)^2)      (Trowbridge-Reitz / GGX)
//                V = G2 / (4 cos_i cos_o) = 0.5 / (cos_o sqrt(cos_i^2 (1 - alpha^2) + alpha^2)
//                                              + cos_i sqrt(cos_o^2 (1 - alpha^2) + alpha^2))
//                    (Smith height-correlated masking-shadowing, Heitz 2014, in Filament's form)
//                F = F0 + (1 - F0) (1 - w_i . h)^5                        (Schlick; F0 is the weight)
//   lambert with fresnel_mix (glTF only): f = albedo / pi (1 - F), F = 0.04 + 0.96 (1 - w_i . h)^5,
//                the dielectric Fresnel (ior 1.5) of the glTF specification's fresnel_mix (Appendix B)
// A Brdf is a sum of lobes. The glTF metallic-roughness material (glTF 2.0 Appendix B,
//   mix(fresnel_mix(ior 1.5, diffuse(baseColor), ggx), conductor_fresnel(baseColor, ggx), metallic))
// maps to
//   lambert(albedo = baseColor (1 - metallic), fresnel_mix) + ggx(roughness, F0 = mix(0.04, baseColor, metallic))
// (the two specular terms add up to one ggx lobe because Schlick's F is linear in F0).
//
// EXTENSION BELOW THE HORIZON (what the SH projection integrates; projection.h). The true BRDF is only
// defined for w_o in the upper hemisphere. prt extends it to every w_o by mirroring:
//   fbar(w_i, w_o) = f(w_i, (w_o.x, w_o.y, |w_o.z|)),
// so fbar is continuous and even in w_o.z, Lambert's fbar is constant on the sphere (its projection
// is exact with one coefficient), and the outgoing radiance a projected BRDF reconstructs for a view
// direction below the horizon is that of its mirror image. Incoming directions below the horizon get
// the cosine factor max(cos theta_i, 0) = 0.
//
// SPEC STRINGS (the CLI's --brdf):
//   SPEC  := LOBE ('+' LOBE)*   or the path of a .json material file (below)
//   LOBE  := TYPE [':' KEY '=' VALUE (',' KEY '=' VALUE)*]
//   VALUE := a number, or R/G/B (three numbers separated by '/') where a colour is accepted
//   lambert:albedo=A,fresnel_mix=0|1         (alias kd; defaults 0.8, 0)
//   phong:exponent=N,ks=S,kd=D               (defaults 32, 1, 0; kd adds a lambert lobe)
//   blinn:exponent=N,ks=S,kd=D               (alias blinn-phong; defaults 32, 1, 0)
//   ggx:roughness=R,f0=F,albedo=A            (alias kd for albedo; defaults 0.5, 0.04, 0)
//   gltf:basecolor=C,metallic=M,roughness=R  (glTF defaults 1, 1, 1)
// e.g. "lambert:albedo=0.8", "phong:exponent=32,ks=0.5,kd=0.3", "ggx:roughness=0.3,f0=0.04,albedo=0.5",
// "lambert:albedo=0.6/0.3/0.2+blinn:exponent=64,ks=0.2". Ranges: colours in [0, 1], exponent in
// [0, 100000], roughness in [0.01, 1], metallic in [0, 1].
//
// MATERIAL FILES (.json): one lobe object {"type": "phong", "exponent": 32, "ks": 0.5, "kd": 0.3}
// (the SPEC keys; colours as a number or [r, g, b]), or {"lobes": [lobe, lobe, ...]}, or a glTF 2.0
// material object {"pbrMetallicRoughness": {"baseColorFactor": [r, g, b, a], "metallicFactor": m,
// "roughnessFactor": r}} (missing factors take glTF's defaults; textures are ignored).
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace prt::brdf {

enum class LobeType { lambert, phong, blinn_phong, ggx };

/// One lobe of a BRDF. `weight` is albedo (lambert), ks (phong, blinn-phong) or F0 (ggx).
struct Lobe {
  LobeType type = LobeType::lambert;
  glm::dvec3 weight{0.8};
  double exponent = 0.0;   ///< phong, blinn-phong: the exponent n >= 0
  double roughness = 0.0;  ///< ggx: perceptual roughness in [0.01, 1]; alpha = roughness^2
  bool fresnel_mix = false;  ///< lambert: times (1 - F) of a dielectric with F0 = 0.04 (glTF's diffuse)
};

/// A BRDF: the sum of its lobes (lambert lobes are merged by parse_brdf: one plain, one fresnel_mix).
struct Brdf {
  std::vector<Lobe> lobes;
  bool empty() const { return lobes.empty(); }
  /// True if every lobe's weight has r = g = b (then one colour channel describes it).
  bool is_grey() const;
};

/// The most lobes a BRDF may have after lambert lobes are merged (docs/formats.md, "Limits").
inline constexpr int kMaxLobes = 16;

/// Parses a SPEC string or a .json material file (see the top of this header). Throws prt::Error with
/// one line "--brdf: <problem>" (or "<file>: <problem>" for a material file) for an unknown lobe or key,
/// a malformed number, a value out of range, more than kMaxLobes lobes, or an empty spec.
Brdf parse_brdf(const std::string& spec);

/// Sum of the weights of the lambert lobes whose fresnel_mix equals `fresnel_mix` into `sum`; false
/// (and sum 0) if there is no such lobe.
bool lambert_weight(const Brdf& brdf, bool fresnel_mix, glm::dvec3& sum);

/// The canonical SPEC string of a BRDF (numbers with 9 significant digits, every parameter written):
/// parse_brdf(to_spec(b)) gives b back to within 1e-9 relative.
std::string to_spec(const Brdf& brdf);

/// The scalar shapes a BRDF is a weighted sum of (the unit the projection works in): the lobes'
/// functions without their colour. A ggx lobe is two shapes, because Schlick's F is linear in F0:
/// F = F0 (1 - s) + s with s = (1 - w_i . h)^5.
enum class Shape {
  lambert,      ///< 1 / pi
  phong,        ///< (n + 2) / (2 pi) max(r . w_o, 0)^n
  blinn_phong,  ///< (n + 8) / (8 pi) (h.z)^n
  ggx_f0,       ///< D V (1 - s): weighted by F0
  ggx_edge,     ///< D V s: weighted by 1
  lambert_fresnel,  ///< 0.96 (1 - s) / pi, s = (1 - w_i . h)^5: glTF's fresnel_mix diffuse (last: the
                    ///< shaders number the shapes in this order, shaders/sun_light.glsl)
};

/// One scalar shape with its RGB weight: f = sum over terms of weight * shape.
struct Term {
  Shape shape = Shape::lambert;
  double parameter = 0.0;  ///< exponent (phong, blinn-phong) or roughness (ggx_*); unused for lambert
  glm::dvec3 weight{1.0};
};

/// The terms of a BRDF, in lobe order; the plain lambert lobes summed into the first term (if any), the
/// fresnel_mix lambert lobes into the next.
std::vector<Term> terms(const Brdf& brdf);

/// The value of one shape at (w_i, w_o) in the local frame: the true BRDF shape for w_o.z >= 0, its
/// mirror extension fbar for w_o.z < 0 (see the top). Preconditions: unit vectors, w_i.z > 0.
double eval_shape(Shape shape, double parameter, const glm::dvec3& w_i, const glm::dvec3& w_o);

/// The BRDF fbar(w_i, w_o) per channel (sum of its terms). Preconditions as eval_shape.
glm::dvec3 eval(const Brdf& brdf, const glm::dvec3& w_i, const glm::dvec3& w_o);

/// fbar(w_i, w_o) max(w_i.z, 0): the cosine-weighted BRDF that the SH matrix projects; 0 for
/// w_i.z <= 0. Unit vectors.
glm::dvec3 eval_cosine(const Brdf& brdf, const glm::dvec3& w_i, const glm::dvec3& w_o);

/// Angular width (radians) of a shape's lobe around the mirror direction, for quadrature grading:
/// pi for lambert (both kinds), 1 / sqrt(n + 1) for phong, 2 / sqrt(n + 1) for blinn-phong, 2 roughness^2 for ggx.
double lobe_width(Shape shape, double parameter);

}  // namespace prt::brdf
