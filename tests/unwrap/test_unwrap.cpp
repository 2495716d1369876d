// src/unwrap against closed forms: a flat grid and a developable cylinder strip flatten to a
// similarity of their surface; folded and self-overlapping maps are caught; charts split at hard edges.
#include <catch2/catch.hpp>

#include <cmath>

#include <glm/geometric.hpp>

#include "unwrap/charts.h"
#include "unwrap/embedding.h"
#include "unwrap/lscm.h"
#include "unwrap/unwrap.h"

namespace {

using namespace prt;

// A grid of n x n quads over (s, t) in [0, 1]^2 mapped by `at` (two triangles per quad, welded).
template <class F>
mesh::Mesh grid(int n, F at) {
  mesh::Mesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      glm::vec3 p, normal;
      at(double(i) / n, double(j) / n, p, normal);
      m.positions.push_back(p);
      m.normals.push_back(normal);
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const std::uint32_t a = std::uint32_t(j * (n + 1) + i), b = a + 1, c = a + std::uint32_t(n) + 2, d = a + std::uint32_t(n) + 1;
      m.indices.insert(m.indices.end(), {a, b, c, a, c, d});
    }
  return m;
}

// Largest relative spread of UV edge length / 3D edge length over all edges, and whether every UV
// triangle keeps the orientation.
void similarity_error(const mesh::Mesh& m, const std::vector<glm::vec2>& uv, double& spread, bool& oriented) {
  double lo = 1e300, hi = 0.0;
  oriented = true;
  for (std::size_t t = 0; t < m.triangle_count(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const std::size_t a = 3 * t + std::size_t(k), b = 3 * t + std::size_t(k + 1) % 3;
      const double ratio = glm::length(glm::dvec2(uv[a] - uv[b])) / glm::length(glm::dvec3(m.positions[m.indices[a]] - m.positions[m.indices[b]]));
      lo = std::min(lo, ratio), hi = std::max(hi, ratio);
    }
    const glm::dvec2 e1 = glm::dvec2(uv[3 * t + 1] - uv[3 * t]), e2 = glm::dvec2(uv[3 * t + 2] - uv[3 * t]);
    oriented = oriented && e1.x * e2.y - e1.y * e2.x > 0.0;  // v down: counter-clockwise in (u, v) as stored
  }
  spread = hi / lo - 1.0;
}

// Unwraps `m` for a size x size atlas: one chart whose edge length ratios (UV / 3D) agree to `tolerance`.
void check_similarity(const mesh::Mesh& m, int size, double tolerance) {
  unwrap::UnwrapReport report;
  const std::vector<glm::vec2> uv = unwrap::unwrap(m, unwrap::UnwrapOptions{size, size, 2, 60.0, 1, ""}, &report);
  CHECK(report.charts == 1);
  double spread = 0.0;
  bool oriented = false;
  similarity_error(m, uv, spread, oriented);
  INFO("spread " << spread);
  CHECK(spread < tolerance);
  CHECK(oriented);
}

}  // namespace

TEST_CASE("unwrap: a flat grid is one chart mapped by a similarity (edge length ratios equal to 1e-5)", "[unwrap]") {
  check_similarity(grid(8, [](double s, double t, glm::vec3& p, glm::vec3& n) {
                     p = glm::vec3(float(2.0 * s), 0.3f, float(-1.5 * t + 0.2 * s));
                     n = glm::vec3(0.0f, 1.0f, 0.0f);
                   }),
                   256, 1e-5);
}

TEST_CASE("unwrap: a developable cylinder strip (50 degrees of arc) unrolls isometrically up to scale", "[unwrap]") {
  // Float UVs of a 512-texel atlas: about 1e-7 / edge length in UV.
  check_similarity(grid(10, [](double s, double t, glm::vec3& p, glm::vec3& n) {
                     const double a = (s - 0.5) * 50.0 * 3.14159265358979323846 / 180.0;
                     p = glm::vec3(float(std::sin(a)), float(std::cos(a)), float(3.0 * t));
                     n = glm::vec3(float(std::sin(a)), float(std::cos(a)), 0.0f);
                   }),
                   512, 1e-4);
}

TEST_CASE("unwrap: charts split at hard edges and at the normal cone but not across smooth edges", "[unwrap]") {
  // Two faces of a box sharing an edge, with split normals (a hard edge): two charts. The same two
  // faces with one shared normal (a smooth edge) at 90 degrees: the cone (60) still splits them.
  mesh::Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}, {0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}};
  m.normals = {{0, 1, 0}, {0, 1, 0}, {0, 1, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  m.indices = {0, 3, 2, 0, 2, 1, 4, 7, 6, 4, 6, 5};
  const unwrap::Surface hard = unwrap::build_surface(m);
  CHECK(hard.neighbour[2] == 1);                     // the floor's diagonal (2, 0) joins its two triangles
  CHECK(hard.neighbour[5] == unwrap::kNoNeighbour);  // edge (1, 0) of triangle 1 meets triangle 2 across a hard edge
  CHECK(unwrap::make_charts(m, hard, {60.0}).size() == 2);
  m.normals.assign(8, glm::normalize(glm::vec3(0, 1, 1)));
  const unwrap::Surface smooth = unwrap::build_surface(m);
  CHECK(smooth.neighbour[5] == 2);
  CHECK(unwrap::make_charts(m, smooth, {60.0}).size() == 2);
  // The wall leaning back to 45 degrees from the floor: one chart for a 60-degree cone, two for 30.
  m.positions[5] = {0, 1, -1};
  m.positions[6] = {1, 1, -1};
  const unwrap::Surface leaning = unwrap::build_surface(m);
  CHECK(unwrap::make_charts(m, leaning, {60.0}).size() == 1);
  CHECK(unwrap::make_charts(m, leaning, {30.0}).size() == 2);
}

TEST_CASE("unwrap: a folded triangle and a border that crosses itself are not embeddings", "[unwrap]") {
  // A fan of 4 triangles around a centre vertex (welded, one chart).
  mesh::Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 0, -1}, {-1, 0, 0}, {0, 0, 1}};
  m.normals.assign(5, glm::vec3(0, 1, 0));
  m.indices = {0, 1, 2, 0, 2, 3, 0, 3, 4, 0, 4, 1};
  const unwrap::Surface s = unwrap::build_surface(m);
  unwrap::FlatChart chart{{0, 1, 2, 3}, {}};
  unwrap::planar_chart(m, chart);
  CHECK(unwrap::is_embedding(m, s, chart));
  // Fold: swap the centre's UV across vertex 1 in every corner that uses it.
  unwrap::FlatChart folded = chart;
  for (std::size_t c = 0; c < 12; ++c)
    if (m.indices[c] == 0) folded.corner_uv[c] = chart.corner_uv[1] * 2.0 - chart.corner_uv[0];
  CHECK(unwrap::count_folds(m, folded) > 0);
  CHECK_FALSE(unwrap::is_embedding(m, s, folded));
  // Two separate triangles flattened on top of each other: no fold, but their borders cross.
  mesh::Mesh pair;
  pair.positions = {{0, 0, 0}, {1, 0, 0}, {0, 0, -1}, {0.2f, 0, -0.2f}, {1.2f, 0, -0.2f}, {0.2f, 0, -1.2f}};
  pair.normals.assign(6, glm::vec3(0, 1, 0));
  pair.indices = {0, 1, 2, 3, 4, 5};
  const unwrap::Surface ps = unwrap::build_surface(pair);
  unwrap::FlatChart both{{0, 1}, {}};
  unwrap::planar_chart(pair, both);
  CHECK(unwrap::count_folds(pair, both) == 0);
  CHECK(unwrap::border_crosses(ps, both));
}
