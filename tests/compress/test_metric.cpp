// The compression metric (compress/metric.h) against brute force: |G dT|^2 must equal the squared
// shaded error averaged over uniformly random rotations of the lighting, here estimated by Monte
// Carlo over rotations (quaternions from a 4D normal: uniform on SO(3)) with the transfer shaded by
// explicit loops (diffuse: dT . R L; glossy: B (dM R L) with the projected BRDF). The metric code
// itself only uses the lighting's band energies and B^T B, so the two share nothing.
#include <catch2/catch.hpp>

#include <random>

#include <glm/geometric.hpp>

#include <glm/gtc/quaternion.hpp>

#include "brdf/brdf.h"
#include "brdf/projection.h"
#include "compress/metric.h"
#include "sh/rotation.h"
#include "support/random_draws.h"

using namespace prt;

namespace {

constexpr int kRotations = 40000;

using prt::test::random_rotation;

sh::RgbCoefficients random_lighting(std::mt19937_64& rng, int bands) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  sh::RgbCoefficients l(bands);
  for (std::size_t j = 0; j < l.values.size(); ++j) {
    const double decay = 1.0 / (1.0 + static_cast<double>(j));  // an uneven spectrum, as real lighting has
    l.values[j] = decay * test::draw_vec3<double>(rng, u);
  }
  return l;
}

std::vector<float> random_values(std::mt19937_64& rng, std::size_t n) {
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<float> v(n);
  for (float& x : v) x = u(rng);
  return v;
}

double metric_norm2(const compress::Metric& metric, const std::vector<float>& x) {
  std::vector<float> g(x.size());
  compress::apply_metric(metric, x.data(), g.data(), 1, false);
  double s = 0.0;
  for (float v : g) s += static_cast<double>(v) * v;
  return s;
}

// Shaded error of one section of the transfer difference dt (offset `at`) under lighting l, per colour.
glm::dvec3 shaded_error(const transfer::Header& h, const float* dt, const sh::RgbCoefficients& l, const brdf::BrdfMatrix* b,
                        std::vector<double>& outgoing) {
  const int n_in = static_cast<int>(h.bands * h.bands);
  glm::dvec3 total(0.0);
  for (int c = 0; c < 3; ++c) {
    const int channel = h.channels == 3 ? c : 0;
    if (!transfer::is_glossy(h.kind)) {
      double s = 0.0;
      for (int j = 0; j < n_in; ++j) s += dt[static_cast<std::size_t>(channel * n_in + j)] * l.values[j][c];
      total[c] = s;
      continue;
    }
    const int n_out = static_cast<int>(h.bands_out * h.bands_out);
    std::vector<double> t(static_cast<std::size_t>(n_out), 0.0);
    for (int k = 0; k < n_out; ++k)
      for (int j = 0; j < n_in; ++j) t[k] += dt[static_cast<std::size_t>((channel * n_out + k) * n_in + j)] * l.values[j][c];
    const double* bc = b->for_colour(c);
    for (int k = 0; k < n_out; ++k) {
      double o = 0.0;
      for (int i = 0; i < n_out; ++i) o += bc[k * n_out + i] * t[i];
      outgoing[static_cast<std::size_t>(c * n_out + k)] += o;
    }
  }
  return total;
}

// Mean over random rotations R of the squared shaded error of dt = [dT] or [dT, dT_b]: dT under R sky,
// dT_b under R discs (one rotation for both), summed over colours (glossy: over outgoing coefficients).
double rotation_average(const transfer::Header& h, const std::vector<float>& dt, const sh::RgbCoefficients& sky,
                        const sh::RgbCoefficients* discs, const brdf::BrdfMatrix* b, std::mt19937_64& rng) {
  const std::size_t D = static_cast<std::size_t>(h.values_per_vertex());
  std::vector<double> outgoing(3 * h.bands_out * h.bands_out);
  double sum = 0.0;
  for (int i = 0; i < kRotations; ++i) {
    const sh::Rotation r(sky.bands, random_rotation(rng));
    std::fill(outgoing.begin(), outgoing.end(), 0.0);
    glm::dvec3 e = shaded_error(h, dt.data(), r.apply(sky), b, outgoing);
    if (discs) e += shaded_error(h, dt.data() + D, r.apply(*discs), b, outgoing);
    sum += glm::dot(e, e);
    for (double o : outgoing) sum += o * o;
  }
  return sum / kRotations;
}

transfer::Header header(transfer::Kind kind, int bands, int bands_out, int channels) {
  transfer::Header h;
  h.kind = kind;
  h.bands = static_cast<std::uint32_t>(bands);
  h.bands_out = static_cast<std::uint32_t>(bands_out);
  h.channels = static_cast<std::uint32_t>(channels);
  h.vertex_count = 1;
  return h;
}

}  // namespace

TEST_CASE("Compression metric: |G dT|^2 is the shaded error averaged over lighting rotations (diffuse)", "[compress][metric]") {
  std::mt19937_64 rng(7);
  for (int channels : {1, 3}) {
    const transfer::Header h = header(transfer::Kind::shadowed, 4, 0, channels);
    const sh::RgbCoefficients l = random_lighting(rng, 4);
    const compress::Metric metric = compress::shaded_metric(h, 1, {&l, nullptr}, nullptr);
    REQUIRE(metric.dimension == h.values_per_vertex());
    for (int trial = 0; trial < 2; ++trial) {
      const std::vector<float> dt = random_values(rng, metric.dimension);
      // Monte Carlo over 40000 rotations: relative standard error ~0.7%; bound 4%.
      CHECK(metric_norm2(metric, dt) == Approx(rotation_average(h, dt, l, nullptr, nullptr, rng)).epsilon(0.04));
    }
    // With the bounce-only section, lit by the discs' SH, turned by the same rotation as the sky.
    const sh::RgbCoefficients discs = random_lighting(rng, 4);
    const compress::Metric both = compress::shaded_metric(h, 2, {&l, &discs}, nullptr);
    REQUIRE(both.dimension == 2 * h.values_per_vertex());
    const std::vector<float> dt = random_values(rng, both.dimension);
    CHECK(metric_norm2(both, dt) == Approx(rotation_average(h, dt, l, &discs, nullptr, rng)).epsilon(0.04));
  }
  // No lighting: plain L2.
  CHECK(compress::shaded_metric(header(transfer::Kind::shadowed, 4, 0, 1), 1, {}, nullptr).identity);
}

TEST_CASE("Compression metric: glossy through the BRDF, and G^-1 undoes G", "[compress][metric]") {
  std::mt19937_64 rng(11);
  const brdf::BrdfMatrix b = brdf::project(brdf::parse_brdf("phong:exponent=8,ks=0.6,kd=0.3"), 3);
  for (int channels : {1, 3}) {
    const transfer::Header h = header(transfer::Kind::glossy_shadowed, 3, 3, channels);
    const sh::RgbCoefficients l = random_lighting(rng, 3);
    const compress::Metric metric = compress::shaded_metric(h, 1, {&l, nullptr}, &b);
    const std::vector<float> dm = random_values(rng, metric.dimension);
    CHECK(metric_norm2(metric, dm) == Approx(rotation_average(h, dm, l, nullptr, &b, rng)).epsilon(0.04));
    const sh::RgbCoefficients discs = random_lighting(rng, 3);
    const compress::Metric both = compress::shaded_metric(header(transfer::Kind::glossy_interreflected, 3, 3, channels), 2, {&l, &discs}, &b);
    const std::vector<float> dm2 = random_values(rng, both.dimension);
    CHECK(metric_norm2(both, dm2) == Approx(rotation_average(h, dm2, l, &discs, &b, rng)).epsilon(0.04));
    // Round trip through G and G^-1 (condition number <= 1e3, float storage): 1e-4 of the largest value.
    std::vector<float> there(dm.size()), back(dm.size());
    compress::apply_metric(metric, dm.data(), there.data(), 1, false);
    compress::apply_metric(metric, there.data(), back.data(), 1, true);
    for (std::size_t i = 0; i < dm.size(); ++i) CHECK(back[i] == Approx(dm[i]).margin(1e-4));
  }
  // A difference the BRDF cannot see costs (almost) nothing: lambert's B reads only the zonal
  // coefficients (l, 0) of the transferred radiance, so a change of row (l=1, m=1) is invisible.
  const brdf::BrdfMatrix lambert = brdf::project(brdf::parse_brdf("lambert:albedo=0.8"), 3);
  const compress::Metric metric = compress::shaded_metric(header(transfer::Kind::glossy_shadowed, 3, 3, 1), 1, {}, &lambert);
  std::vector<float> seen(metric.dimension, 0.0f), unseen(metric.dimension, 0.0f);
  for (int j = 0; j < 9; ++j) seen[static_cast<std::size_t>(2 * 9 + j)] = unseen[static_cast<std::size_t>(3 * 9 + j)] = 1.0f;
  INFO("row (1,0): " << metric_norm2(metric, seen) << ", row (1,1): " << metric_norm2(metric, unseen));
  CHECK(metric_norm2(metric, unseen) < 1e-5 * metric_norm2(metric, seen));
}

TEST_CASE("Compression metric: several BRDFs weigh the shaded error by their shares of the points", "[compress][metric]") {
  // The metric of two BRDFs with shares 0.3 and 0.7 is the shares' mean of each BRDF's rotation-averaged
  // shaded error (Monte Carlo here, through each BRDF's matrix); shares (1, 0) give the first BRDF's metric.
  std::mt19937_64 rng(23);
  const brdf::BrdfMatrix shiny = brdf::project(brdf::parse_brdf("phong:exponent=12,ks=0.7,kd=0.2"), 3);
  const brdf::BrdfMatrix matte = brdf::project(brdf::parse_brdf("lambert:albedo=0.5/0.7/0.9"), 3);
  const transfer::Header h = header(transfer::Kind::glossy_shadowed, 3, 3, 3);
  const sh::RgbCoefficients l = random_lighting(rng, 3);
  const compress::Metric mixed = compress::shaded_metric(h, 1, {&l, nullptr}, {shiny, matte}, {0.3, 0.7});
  const std::vector<float> dm = random_values(rng, mixed.dimension);
  const double expected = 0.3 * rotation_average(h, dm, l, nullptr, &shiny, rng) + 0.7 * rotation_average(h, dm, l, nullptr, &matte, rng);
  CHECK(metric_norm2(mixed, dm) == Approx(expected).epsilon(0.04));
  const double shiny_only = rotation_average(h, dm, l, nullptr, &shiny, rng);
  CHECK(std::abs(expected - shiny_only) > 0.1 * shiny_only);  // the shares matter on this draw
  const compress::Metric first = compress::shaded_metric(h, 1, {&l, nullptr}, {shiny, matte}, {1.0, 0.0});
  CHECK(metric_norm2(first, dm) == Approx(metric_norm2(compress::shaded_metric(h, 1, {&l, nullptr}, &shiny), dm)).epsilon(1e-9));
  CHECK_THROWS_WITH(compress::shaded_metric(h, 1, {&l, nullptr}, {shiny, matte}, {1.0}), Catch::Contains("2 BRDFs, 1 shares"));
}
