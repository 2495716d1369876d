// The glossy baker against independent truth: the unshadowed identity on a convex sphere (SH functions
// compared pointwise, no rotation code), Lambert against the diffuse baker, brute-force Monte Carlo
// visibility and an independent bounce gather (world-frame directions from std::mt19937, double, no
// sample frame), non-square matrices, determinism, option errors.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <random>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "bake/bake.h"
#include "brdf/brdf.h"
#include "brdf/frame.h"
#include "brdf/projection.h"
#include "core/error.h"
#include "sh/basis.h"
#include "sh/quadrature.h"
#include "shade/glossy.h"
#include "shade/shade.h"
#include "support/random_draws.h"
#include "support/shapes.h"
#include "trace/scene.h"

using namespace prt;

namespace {

bake::BakeOptions glossy_options(transfer::Kind kind, int bands, int samples, const std::string& brdf_spec) {
  bake::BakeOptions o;
  o.kind = kind;
  o.bands = bands;
  o.samples = samples;
  o.brdf = brdf::parse_brdf(brdf_spec);
  return o;
}

sh::RgbCoefficients random_lighting(int bands, std::mt19937_64& rng) {
  std::normal_distribution<double> gauss;
  sh::RgbCoefficients l(bands);
  for (glm::dvec3& v : l.values) v = prt::test::draw_vec3<double>(rng, gauss);
  l.values[0] += glm::dvec3(4.0);
  return l;
}

// Uniform direction on the hemisphere about n (world frame), by rejection from the sphere.
glm::dvec3 uniform_hemisphere(const glm::dvec3& n, std::mt19937_64& rng) {
  const glm::dvec3 d = prt::test::random_direction(rng);
  return glm::dot(d, n) >= 0.0 ? d : -d;
}

// The exact unoccluded matrix, independently: integral over the sphere of y_out(F^T w) y_in(w)^T dw by
// the exact product quadrature (the integrand is a polynomial of degree <= 2 (bands - 1)).
std::vector<double> unoccluded_matrix(const glm::dmat3& frame, int bands, int bands_out) {
  const int n_in = bands * bands, n_out = bands_out * bands_out;
  const sh::SphereQuadrature q = sh::gauss_product_quadrature_for_bands(bands, bands);
  std::vector<double> m(static_cast<std::size_t>(n_out) * n_in, 0.0), y_in(n_in), y_out(n_out);
  for (std::size_t s = 0; s < q.directions.size(); ++s) {
    sh::eval(bands, q.directions[s], y_in.data());
    sh::eval(bands_out, glm::transpose(frame) * q.directions[s], y_out.data());
    for (int k = 0; k < n_out; ++k)
      for (int j = 0; j < n_in; ++j) m[k * n_in + j] += q.weights[s] * y_out[k] * y_in[j];
  }
  return m;
}

}  // namespace

TEST_CASE("on a convex sphere glossy shadowed is the unshadowed transfer: the lighting in the local frame", "[glossy]") {
  // T = M L must be the function w -> L(F w) on every local direction w (upper and lower hemisphere),
  // checked pointwise with the basis only (no SH rotation code).
  const mesh::Mesh m = test::uv_sphere(16, 32);
  const int bands = 5, n = 25;
  const transfer::TransferData t = bake::bake(m, glossy_options(transfer::Kind::glossy_shadowed, bands, 256, "phong:exponent=10"));
  REQUIRE(t.header.bands_out == 5);
  REQUIRE(t.header.channels == 1);
  std::mt19937_64 rng(2);
  std::vector<double> light(n), y(n), local(n);
  std::normal_distribution<double> gauss;
  for (double& v : light) v = gauss(rng);
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    const glm::dmat3 frame = brdf::shading_frame(glm::dvec3(m.normals[v]));
    const float* matrix = t.values.data() + v * n * n;
    for (int k = 0; k < n; ++k) {
      local[k] = 0.0;
      for (int j = 0; j < n; ++j) local[k] += matrix[k * n + j] * light[j];
    }
    for (int trial = 0; trial < 4; ++trial) {
      const glm::dvec3 w = prt::test::random_direction(rng);
      sh::eval(bands, w, y.data());
      double transferred = 0.0;
      for (int k = 0; k < n; ++k) transferred += local[k] * y[k];
      sh::eval(bands, frame * w, y.data());
      double lighting = 0.0;
      for (int k = 0; k < n; ++k) lighting += light[k] * y[k];
      REQUIRE(transferred == Approx(lighting).margin(2e-5));
    }
  }
  // Interreflection adds nothing on a convex shape (no ray hits a front face).
  bake::BakeOptions o = glossy_options(transfer::Kind::glossy_interreflected, bands, 256, "phong:exponent=10");
  o.bounces = 2;
  const transfer::TransferData inter = bake::bake(m, o);
  REQUIRE(inter.values.size() == t.values.size());
  for (std::size_t i = 0; i < t.values.size(); ++i) REQUIRE(inter.values[i] == t.values[i]);
}

TEST_CASE("with a Lambert BRDF glossy shading equals the diffuse unshadowed transfer on a convex sphere", "[glossy]") {
  const mesh::Mesh m = test::uv_sphere(12, 24);
  const int bands = 4;
  const transfer::TransferData glossy = bake::bake(m, glossy_options(transfer::Kind::glossy_shadowed, bands, 128, "lambert:albedo=0.6"));
  bake::BakeOptions diffuse_options;
  diffuse_options.kind = transfer::Kind::unshadowed;
  diffuse_options.bands = bands;
  diffuse_options.albedo = glm::vec3(0.6f);
  const transfer::TransferData diffuse = bake::bake(m, diffuse_options);
  std::mt19937_64 rng(4);
  const sh::RgbCoefficients lighting = random_lighting(bands, rng);
  const std::vector<glm::vec3> expected = shade::shade_diffuse(diffuse, lighting);
  const brdf::BrdfMatrix b = brdf::project(brdf::parse_brdf("lambert:albedo=0.6"), bands);
  std::vector<glm::vec3> views(m.positions.size());
  for (int trial = 0; trial < 3; ++trial) {
    for (std::size_t v = 0; v < views.size(); ++v) views[v] = glm::vec3(uniform_hemisphere(glm::dvec3(m.normals[v]), rng));
    const std::vector<glm::vec3> got = shade::shade_glossy(glossy, b, lighting, m.normals, views);
    for (std::size_t v = 0; v < got.size(); ++v)
      for (int c = 0; c < 3; ++c) REQUIRE(got[v][c] == Approx(expected[v][c]).margin(2e-5));
  }
}

TEST_CASE("glossy shadowed transfer agrees with brute-force Monte Carlo visibility", "[glossy]") {
  // M_p = U_p - integral over the occluded upper hemisphere of y_out(F^T w) y_in(w)^T dw, with U_p the
  // exact unoccluded matrix (product quadrature) and the integral by 60000 uniform world directions from
  // std::mt19937 per vertex. Tolerance: 5 standard errors per entry plus the baked estimate's own noise.
  const mesh::Mesh m = test::open_box(0.8f, 5);
  const int bands = 3, bands_out = 3, n = 9;
  const int baked_samples = 4096;
  const transfer::TransferData baked = bake::bake(m, glossy_options(transfer::Kind::glossy_shadowed, bands, baked_samples, "lambert"));
  const trace::Scene scene(m);
  std::mt19937_64 rng(17);
  const int rays = 60000;
  int checked = 0;
  trace::RayBatch batch(1);
  std::vector<double> y_in(n), y_out(n);
  for (std::size_t v = 0; v < m.positions.size(); v += 11) {
    const glm::dvec3 normal(m.normals[v]);
    const glm::dmat3 frame = brdf::shading_frame(normal);
    const std::vector<double> exact = unoccluded_matrix(frame, bands, bands_out);
    std::vector<double> sum(n * n, 0.0), sum_sq(n * n, 0.0);
    for (int r = 0; r < rays; ++r) {
      const glm::dvec3 d = uniform_hemisphere(normal, rng);
      batch.clear();
      batch.push(scene.offset_origin(m.positions[v], m.normals[v]), glm::vec3(d));
      scene.occluded(batch);
      if (!batch.is_occluded(0)) continue;
      sh::eval(bands, d, y_in.data());
      sh::eval(bands_out, glm::transpose(frame) * d, y_out.data());
      for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j) {
          const double f = 2.0 * M_PI * y_out[k] * y_in[j];
          sum[k * n + j] += f;
          sum_sq[k * n + j] += f * f;
        }
    }
    for (int i = 0; i < n * n; ++i) {
      const double mean = sum[i] / rays;
      const double stderr_ = std::sqrt(std::max(0.0, sum_sq[i] / rays - mean * mean) / rays);
      const double stderr_baked = stderr_ * std::sqrt(static_cast<double>(rays) / baked_samples);
      INFO("vertex " << v << " entry " << i);
      REQUIRE(baked.values[v * n * n + i] == Approx(exact[i] - mean).margin(5 * std::hypot(stderr_, stderr_baked) + 1e-4));
    }
    ++checked;
  }
  CHECK(checked >= 15);
}

TEST_CASE("a glossy bounce agrees with an independent gather of the direct pass's outgoing radiance", "[glossy]") {
  // One bounce on an open box with a glossy BRDF: M^1_p = integral over the upper hemisphere of
  // y_out(F_p^T w) r(w)^T dw, where r(w) is the radiance row of the front-face hit q:
  // sum over corners c of bary_c Y(F_c^T (-w))^T B M^0_c. Estimated here with std::mt19937 world
  // directions, double precision, M^0 from a glossy-shadowed bake with the same samples and seed.
  const mesh::Mesh m = test::open_box(1.0f, 4);
  const int bands = 3, n = 9;
  const std::string spec = "phong:exponent=6,ks=0.5,kd=0.4";
  const int baked_samples = 2048;
  const transfer::TransferData direct = bake::bake(m, glossy_options(transfer::Kind::glossy_shadowed, bands, baked_samples, spec));
  bake::BakeOptions o = glossy_options(transfer::Kind::glossy_interreflected, bands, baked_samples, spec);
  o.bounces = 1;
  const transfer::TransferData inter = bake::bake(m, o);
  const brdf::BrdfMatrix b = brdf::project(brdf::parse_brdf(spec), bands);
  // P_q = B M^0_q in double.
  std::vector<double> outgoing(m.positions.size() * n * n, 0.0);
  for (std::size_t q = 0; q < m.positions.size(); ++q)
    for (int k = 0; k < n; ++k)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) outgoing[(q * n + k) * n + i] += b.channel(0)[k * n + j] * direct.values[(q * n + j) * n + i];
  const trace::Scene scene(m);
  std::mt19937_64 rng(23);
  const int rays = 20000;
  trace::RayBatch batch(1);
  std::vector<double> y(n), y_out(n), row(n);
  int checked = 0;
  for (std::size_t v = 0; v < m.positions.size(); v += 7) {
    const glm::dvec3 normal(m.normals[v]);
    const glm::dmat3 frame = brdf::shading_frame(normal);
    std::vector<double> sum(n * n, 0.0), sum_sq(n * n, 0.0);
    for (int r = 0; r < rays; ++r) {
      const glm::dvec3 d = uniform_hemisphere(normal, rng);
      batch.clear();
      batch.push(scene.offset_origin(m.positions[v], m.normals[v]), glm::vec3(d));
      scene.intersect(batch);
      const trace::HitResult hit = batch.hit(0);
      if (!hit.hit() || glm::dot(glm::dvec3(hit.ng), d) >= 0.0) continue;
      const std::uint32_t* tri = m.indices.data() + 3 * hit.prim_id;
      const double bary[3] = {1.0 - hit.u - hit.v, hit.u, hit.v};
      std::fill(row.begin(), row.end(), 0.0);
      for (int c = 0; c < 3; ++c) {
        sh::eval(bands, glm::transpose(brdf::shading_frame(glm::dvec3(m.normals[tri[c]]))) * (-d), y.data());
        for (int k = 0; k < n; ++k)
          for (int i = 0; i < n; ++i) row[i] += bary[c] * y[k] * outgoing[(tri[c] * n + k) * n + i];
      }
      sh::eval(bands, glm::transpose(frame) * d, y_out.data());
      for (int k = 0; k < n; ++k)
        for (int i = 0; i < n; ++i) {
          const double f = 2.0 * M_PI * y_out[k] * row[i];
          sum[k * n + i] += f;
          sum_sq[k * n + i] += f * f;
        }
    }
    for (int i = 0; i < n * n; ++i) {
      const double mean = sum[i] / rays;
      const double stderr_ = std::sqrt(std::max(0.0, sum_sq[i] / rays - mean * mean) / rays);
      const double stderr_baked = stderr_ * std::sqrt(static_cast<double>(rays) / baked_samples);
      const double bounce = inter.values[v * n * n + i] - direct.values[v * n * n + i];
      INFO("vertex " << v << " entry " << i);
      REQUIRE(bounce == Approx(mean).margin(5 * std::hypot(stderr_, stderr_baked) + 2e-4));
    }
    ++checked;
  }
  CHECK(checked >= 15);
}

TEST_CASE("non-square glossy transfer is the leading rows of the square one", "[glossy]") {
  const mesh::Mesh m = test::open_box(0.8f, 3);
  const transfer::TransferData square = bake::bake(m, glossy_options(transfer::Kind::glossy_shadowed, 5, 128, "ggx:roughness=0.4"));
  bake::BakeOptions o = glossy_options(transfer::Kind::glossy_shadowed, 5, 128, "ggx:roughness=0.4");
  o.bands_out = 3;
  const transfer::TransferData narrow = bake::bake(m, o);
  REQUIRE(narrow.header.bands_out == 3);
  REQUIRE(narrow.header.values_per_vertex() == 9 * 25);
  for (std::size_t v = 0; v < m.positions.size(); ++v)
    for (int k = 0; k < 9; ++k)
      for (int j = 0; j < 25; ++j) REQUIRE(narrow.values[(v * 9 + k) * 25 + j] == Approx(square.values[(v * 25 + k) * 25 + j]).margin(1e-6));
}

TEST_CASE("glossy bakes are identical for any thread count, RGB BRDFs give RGB interreflection", "[glossy]") {
  const mesh::Mesh m = test::torus(1.0f, 0.45f, 24, 12);
  bake::BakeOptions o = glossy_options(transfer::Kind::glossy_interreflected, 3, 64, "lambert:albedo=0.5/0.3/0.1+blinn:exponent=20,ks=0.3");
  o.bounces = 2;
  o.threads = 1;
  const transfer::TransferData one = bake::bake(m, o);
  o.threads = 2;
  const transfer::TransferData two = bake::bake(m, o);
  REQUIRE(one.header.channels == 3);
  REQUIRE(one.values.size() == two.values.size());
  CHECK(std::memcmp(one.values.data(), two.values.data(), one.values.size() * 4) == 0);
  CHECK(one.header.parameters_json == two.header.parameters_json);
  // The direct part is the same in every channel; the bounce light differs (red > blue here).
  double red = 0, blue = 0;
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    red += one.values[(v * 3 + 0) * 81];
    blue += one.values[(v * 3 + 2) * 81];
  }
  CHECK(red > blue);
  o.kind = transfer::Kind::glossy_shadowed;
  o.threads = 1;
  const transfer::TransferData s1 = bake::bake(m, o);
  o.threads = 2;
  const transfer::TransferData s2 = bake::bake(m, o);
  CHECK(s1.header.channels == 1);
  CHECK(std::memcmp(s1.values.data(), s2.values.data(), s1.values.size() * 4) == 0);
}

TEST_CASE("glossy bake options are checked", "[glossy]") {
  const mesh::Mesh m = test::uv_sphere(4, 8);
  bake::BakeOptions o;
  o.kind = transfer::Kind::glossy_shadowed;
  CHECK_THROWS_WITH(bake::bake(m, o), Catch::Contains("transfer needs a BRDF spec"));
  o.brdf = brdf::parse_brdf("lambert");
  o.bands = 3;
  o.bands_out = 4;
  CHECK_THROWS_WITH(bake::bake(m, o), Catch::Contains("bands_out 4 is out of range"));
  o.kind = transfer::Kind::shadowed;
  o.bands_out = 2;
  CHECK_THROWS_WITH(bake::bake(m, o), Catch::Contains("bands_out applies to glossy transfer only"));
}
