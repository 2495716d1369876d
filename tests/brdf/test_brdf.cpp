// BRDF definitions against physics and closed forms (normalization, reciprocity, the mirror
// extension), SPEC strings and material files, and the local shading frame.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <random>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "brdf/brdf.h"
#include "brdf/frame.h"
#include "brdf/graded_rule.h"
#include "core/error.h"
#include "sh/quadrature.h"
#include "support/random_draws.h"
#include "support/run_prt.h"

using namespace prt;

namespace {

glm::dvec3 random_upper(std::mt19937_64& rng) {
  std::normal_distribution<double> gauss;
  for (;;) {
    glm::dvec3 d = prt::test::draw_vec3<double>(rng, gauss);
    if (glm::length(d) < 1e-6) continue;
    d = glm::normalize(d);
    if (std::abs(d.z) < 1e-3) continue;
    d.z = std::abs(d.z);
    return d;
  }
}

// Directional albedo integral over w_o in the upper hemisphere of fbar(w_i, w_o) cos(theta_o), by a
// graded product rule in (theta_o, phi) centred on the mirror direction (independent of projection.cpp's
// choice of grading: finer, 16 nodes per panel).
double directional_albedo(const brdf::Brdf& b, const glm::dvec3& w_i, double width) {
  const double theta_i = std::acos(w_i.z);
  const brdf::detail::Rule1D theta = brdf::detail::graded_rule(0.0, M_PI / 2, theta_i, width / 8, 0.1, 16);
  const brdf::detail::Rule1D phi = brdf::detail::graded_rule(0.0, M_PI, M_PI, width / 8, 0.1, 16);
  double sum = 0.0;
  for (std::size_t a = 0; a < theta.nodes.size(); ++a)
    for (std::size_t c = 0; c < phi.nodes.size(); ++c) {
      const double t = theta.nodes[a], p = phi.nodes[c];
      const glm::dvec3 w_o(std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t));
      sum += 2.0 * theta.weights[a] * phi.weights[c] * std::sin(t) * std::cos(t) * brdf::eval(b, w_i, w_o).r;
    }
  return sum;
}

std::string one_line_error(const std::string& spec) {
  try {
    brdf::parse_brdf(spec);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("normalized phong reflects exactly ks at normal incidence", "[brdf]") {
  // Closed form: integral of (n+2)/(2pi) cos^n(theta) cos(theta) dw = 1 over the hemisphere.
  for (double n : {0.0, 1.0, 8.0, 100.0, 2000.0}) {
    const brdf::Brdf b = brdf::parse_brdf("phong:exponent=" + std::to_string(n) + ",ks=0.7");
    CHECK(directional_albedo(b, {0, 0, 1}, 1.0 / std::sqrt(n + 1)) == Approx(0.7).epsilon(1e-9));
  }
}

TEST_CASE("the GGX distribution is normalized and its directional albedo is at most F0 = 1", "[brdf]") {
  // integral D(h) h.z dh = 1 over the hemisphere, through brdf::eval: at w_o = n (so Lambda(w_o) = 0)
  // the height-correlated Smith term is G2 = 1 / (1 + Lambda(w_i)) (Heitz 2014, "Understanding the
  // Masking-Shadowing Function", eq. 99) with Lambda(w) = (sqrt(1 + alpha^2 tan^2 theta) - 1) / 2, and the
  // half-vector Jacobian is dw_i = 4 (h.w_o) dh (Walter et al. 2007), so with F = 1
  //   integral over w_i of f(w_i, n) cos(theta_i) (1 + Lambda(w_i)) dw_i = integral D(h) (h.n) dh
  // over the half-vectors of the upper hemisphere of w_i, those within 45 degrees of n (theta_i =
  // 2 theta_h). GGX's measure of that cone is tan^2 / (alpha^2 + tan^2) at 45 degrees = 1 / (1 + alpha^2)
  // (its CDF, Walter et al. 2007, eq. 35): 1 - alpha^2 for smooth surfaces, 1/2 at alpha = 1.
  // Gauss-Legendre in cos(theta_i) on panels graded toward the peak at w_i = n; isotropic, so 2 pi in phi.
  for (double roughness : {0.05, 0.3, 0.7, 1.0}) {
    const double alpha2 = std::pow(roughness, 4);
    const brdf::Brdf furnace = brdf::parse_brdf("ggx:roughness=" + std::to_string(roughness) + ",f0=1");
    const brdf::detail::Rule1D rule = brdf::detail::graded_rule(0.0, 1.0, 1.0, alpha2 / 4 + 1e-9, 0.1, 16);
    double sum = 0.0;
    for (std::size_t k = 0; k < rule.nodes.size(); ++k) {
      const double c = rule.nodes[k], s2 = 1.0 - c * c;
      const double lambda = 0.5 * (std::sqrt(1.0 + alpha2 * s2 / (c * c)) - 1.0);
      const double f = brdf::eval(furnace, {std::sqrt(s2), 0.0, c}, {0.0, 0.0, 1.0}).x;
      sum += rule.weights[k] * 2.0 * M_PI * f * c * (1.0 + lambda);
    }
    CHECK(sum == Approx(1.0 / (1.0 + alpha2)).epsilon(1e-9));
    // White furnace with F = 1: single-scattering GGX loses energy (multiple scattering is not
    // modelled), never gains any; smooth surfaces at normal incidence lose almost nothing.
    const brdf::Brdf b = brdf::parse_brdf("ggx:roughness=" + std::to_string(roughness) + ",f0=1");
    for (double theta_deg : {0.0, 45.0, 80.0}) {
      const double t = theta_deg * M_PI / 180.0;
      const double e = directional_albedo(b, {std::sin(t), 0.0, std::cos(t)}, 2.0 * roughness * roughness);
      CHECK(e <= 1.0 + 1e-9);
      if (roughness <= 0.3 && theta_deg == 0.0) CHECK(e >= 0.97);
    }
  }
  // Closed form at alpha = 1, normal incidence: D = 1/pi, V = 0.5 / (1 + cos_o), so
  // E = 2 pi integral_0^1 (1/pi) 0.5 / (1 + t) t dt = 1 - ln 2.
  const brdf::Brdf rough = brdf::parse_brdf("ggx:roughness=1,f0=1");
  CHECK(directional_albedo(rough, {0, 0, 1}, 2.0) == Approx(1.0 - std::log(2.0)).epsilon(1e-10));
  {
  }
}

TEST_CASE("every BRDF is reciprocal, isotropic and mirror-extended below the horizon", "[brdf]") {
  std::mt19937_64 rng(3);
  for (const char* spec : {"phong:exponent=20,ks=0.6", "blinn:exponent=40", "ggx:roughness=0.4,f0=0.3", "lambert:albedo=0.5"}) {
    const brdf::Brdf b = brdf::parse_brdf(spec);
    for (int trial = 0; trial < 200; ++trial) {
      const glm::dvec3 a = random_upper(rng), c = random_upper(rng);
      const double f_ac = brdf::eval(b, a, c).r, f_ca = brdf::eval(b, c, a).r;
      REQUIRE(f_ac == Approx(f_ca).epsilon(1e-12).margin(1e-300));
      // Rotating both directions about z, or mirroring both in y, changes nothing.
      const double angle = 2.0 * M_PI * trial / 200.0, cs = std::cos(angle), sn = std::sin(angle);
      auto rotate = [&](const glm::dvec3& d) { return glm::dvec3(cs * d.x - sn * d.y, sn * d.x + cs * d.y, d.z); };
      REQUIRE(brdf::eval(b, rotate(a), rotate(c)).r == Approx(f_ac).epsilon(1e-10).margin(1e-300));
      REQUIRE(brdf::eval(b, {a.x, -a.y, a.z}, {c.x, -c.y, c.z}).r == Approx(f_ac).epsilon(1e-12).margin(1e-300));
      // fbar(w_i, (x, y, -z)) = f(w_i, (x, y, z)); the cosine factor vanishes for w_i below.
      REQUIRE(brdf::eval(b, a, {c.x, c.y, -c.z}).r == f_ac);
      REQUIRE(brdf::eval_cosine(b, {a.x, a.y, -a.z}, c) == glm::dvec3(0.0));
      REQUIRE(brdf::eval_cosine(b, a, c).r == Approx(f_ac * a.z).epsilon(1e-14));
    }
  }
}

TEST_CASE("SPEC strings parse into lobes and round-trip through to_spec", "[brdf]") {
  brdf::Brdf b = brdf::parse_brdf("phong:exponent=32,ks=0.5,kd=0.3");
  REQUIRE(b.lobes.size() == 2);
  CHECK(b.lobes[0].type == brdf::LobeType::lambert);
  CHECK(b.lobes[0].weight == glm::dvec3(0.3));
  CHECK(b.lobes[1].type == brdf::LobeType::phong);
  CHECK(b.lobes[1].exponent == 32.0);
  CHECK(b.lobes[1].weight == glm::dvec3(0.5));
  CHECK(b.is_grey());

  b = brdf::parse_brdf("lambert:albedo=0.6/0.3/0.2+blinn:exponent=64,ks=0.2");
  REQUIRE(b.lobes.size() == 2);
  CHECK(!b.is_grey());
  CHECK(b.lobes[0].weight == glm::dvec3(0.6, 0.3, 0.2));
  CHECK(b.lobes[1].type == brdf::LobeType::blinn_phong);
  CHECK(brdf::to_spec(b) == "lambert:albedo=0.6/0.3/0.2+blinn:exponent=64,ks=0.2");

  // glTF metallic-roughness: diffuse = base (1 - metallic), F0 = mix(0.04, base, metallic).
  b = brdf::parse_brdf("gltf:basecolor=0.8/0.2/0.1,metallic=0.25,roughness=0.4");
  REQUIRE(b.lobes.size() == 2);
  CHECK(b.lobes[0].weight.r == Approx(0.6));
  CHECK(b.lobes[0].weight.b == Approx(0.075));
  CHECK(b.lobes[1].type == brdf::LobeType::ggx);
  CHECK(b.lobes[1].roughness == 0.4);
  CHECK(b.lobes[1].weight.r == Approx(0.04 * 0.75 + 0.8 * 0.25));
  CHECK(b.lobes[1].weight.g == Approx(0.04 * 0.75 + 0.2 * 0.25));

  // Lambert lobes merge; the canonical spec parses back to the same BRDF.
  b = brdf::parse_brdf("lambert:albedo=0.2+ggx:roughness=0.3,f0=0.04,albedo=0.5");
  REQUIRE(b.lobes.size() == 2);
  CHECK(b.lobes[0].weight == glm::dvec3(0.7));
  const brdf::Brdf again = brdf::parse_brdf(brdf::to_spec(b));
  REQUIRE(again.lobes.size() == b.lobes.size());
  for (std::size_t i = 0; i < b.lobes.size(); ++i) {
    CHECK(again.lobes[i].type == b.lobes[i].type);
    CHECK(again.lobes[i].weight == b.lobes[i].weight);
    CHECK(again.lobes[i].roughness == b.lobes[i].roughness);
  }
  CHECK(brdf::parse_brdf("LAMBERT").lobes[0].weight == glm::dvec3(0.8));
}

TEST_CASE("material files: one lobe, a list of lobes, a glTF material", "[brdf]") {
  const std::string dir = test::fresh_temp_dir("brdf_material");
  auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream(dir + "/" + name) << text;
    return dir + "/" + name;
  };
  brdf::Brdf b = brdf::parse_brdf(write("phong.json", R"({"type": "phong", "exponent": 32, "ks": 0.5, "kd": [0.3, 0.2, 0.1]})"));
  REQUIRE(b.lobes.size() == 2);
  CHECK(b.lobes[0].weight == glm::dvec3(0.3, 0.2, 0.1));
  b = brdf::parse_brdf(write("lobes.json", R"({"lobes": [{"type": "lambert", "albedo": 0.4}, {"type": "ggx", "roughness": 0.3}]})"));
  REQUIRE(b.lobes.size() == 2);
  CHECK(b.lobes[1].weight == glm::dvec3(0.04));
  b = brdf::parse_brdf(write("gltf.json", R"({"name": "gold", "pbrMetallicRoughness": {"baseColorFactor": [1.0, 0.8, 0.3, 1.0], "metallicFactor": 1.0, "roughnessFactor": 0.35}})"));
  REQUIRE(b.lobes.size() == 1);
  CHECK(b.lobes[0].type == brdf::LobeType::ggx);
  CHECK(b.lobes[0].weight == glm::dvec3(1.0, 0.8, 0.3));
  CHECK(b.lobes[0].roughness == 0.35);

  const std::string bad = write("bad.json", R"({"type": "phong", "exponent": "high"})");
  try {
    brdf::parse_brdf(bad);
    FAIL("no error");
  } catch (const Error& e) {
    CHECK(std::string(e.what()).rfind(bad + ": ", 0) == 0);
  }
  CHECK_THROWS_AS(brdf::parse_brdf(dir + "/missing.json"), Error);
}

TEST_CASE("bad BRDF specs give one-line errors naming the problem", "[brdf]") {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"", "empty BRDF spec"},
      {"velvet", "unknown BRDF 'velvet'"},
      {"phong:bogus=1", "unknown parameter 'bogus'"},
      {"phong:exponent=-1", "exponent -1 is out of range"},
      {"phong:exponent=abc", "expected a number"},
      {"phong:exponent=1/2/3", "takes one number"},
      {"phong:ks=1/2", "expected a number or R/G/B"},
      {"ggx:roughness=0", "roughness 0 is out of range"},
      {"lambert:albedo=1.5", "components must lie in [0, 1]"},
      {"lambert+", "empty lobe"},
      {"lambert:albedo", "expected KEY=VALUE"},
      {"lambert:albedo=0.7+lambert:albedo=0.6", "sum to more than 1"},
      {"phong:ks=0.5,ks=0.4", "given twice"},
  };
  for (const auto& [spec, expected] : cases) {
    const std::string message = one_line_error(spec);
    INFO(spec << " -> " << message);
    CHECK(message.find(expected) != std::string::npos);
    CHECK(message.find('\n') == std::string::npos);
  }
}

TEST_CASE("the shading frame is a rotation with z = n, smooth away from +-Y", "[brdf]") {
  std::mt19937_64 rng(5);
  std::normal_distribution<double> gauss;
  for (int trial = 0; trial < 2000; ++trial) {
    glm::dvec3 n = prt::test::random_direction(rng);
    if (trial == 0) n = {0, 1, 0};
    if (trial == 1) n = {0, -1, 0};
    if (trial == 2) n = glm::normalize(glm::dvec3(1e-8, 1, -2e-8));
    const glm::dmat3 f = brdf::shading_frame(n);
    const glm::dmat3 should_be_identity = glm::transpose(f) * f;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) REQUIRE(should_be_identity[i][j] == Approx(i == j ? 1.0 : 0.0).margin(1e-12));
    REQUIRE(glm::determinant(f) == Approx(1.0).epsilon(1e-12));
    REQUIRE(glm::length(f[2] - n) < 1e-15);
    // Smooth: a small change of n (away from the poles) changes the frame by a small amount.
    if (std::abs(n.y) < 0.99) {
      const glm::dvec3 n2 = glm::normalize(n + 1e-6 * prt::test::draw_vec3<double>(rng, gauss));
      const glm::dmat3 f2 = brdf::shading_frame(n2);
      REQUIRE(glm::length(f2[0] - f[0]) < 1e-4);
    }
    // The float version agrees.
    const glm::mat3 ff = brdf::shading_frame(glm::vec3(n));
    REQUIRE(glm::length(glm::dvec3(ff[0]) - f[0]) < 1e-5);
  }
  // The documented formula: n = +z gives the identity, t is horizontal.
  const glm::dmat3 f = brdf::shading_frame(glm::dvec3(0, 0, 1));
  CHECK(f[0] == glm::dvec3(1, 0, 0));
  CHECK(f[1] == glm::dvec3(0, 1, 0));
}
