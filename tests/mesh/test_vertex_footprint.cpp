// mesh::VertexFootprints against closed forms: a point drawn with density proportional to the hat
// function phi_v falls in each triangle of v's one-ring with probability area / ring area, v's own
// barycentric weight b follows Beta(2, 2) (E b = 1/2, E b^2 = 3/10, P(b < 1/4) = 5/32), and the mean
// point is the hat-weighted centroid sum_t A_t (2 v + a + b) / 4 / sum_t A_t (the integral of a linear
// function times phi_v over a triangle). Membership and barycentrics are recomputed here from the
// triangle corners, not taken from the sampler.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <vector>

#include <glm/geometric.hpp>

#include "mesh/vertex_footprint.h"

using namespace prt;

namespace {

// A fan of three triangles of different areas about vertex 0 at (0.1, 0.2, 0.3), not in one plane,
// and an unused vertex 5.
mesh::Mesh fan() {
  mesh::Mesh m;
  m.positions = {{0.1f, 0.2f, 0.3f}, {2.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.5f}, {-1.0f, -0.5f, 0.0f}, {0.5f, -3.0f, 1.0f}, {9.0f, 9.0f, 9.0f}};
  m.normals.assign(m.positions.size(), glm::vec3(0, 0, 1));
  m.indices = {0, 1, 2, 0, 2, 3, 4, 1, 0};
  return m;
}

double area(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) { return 0.5 * glm::length(glm::cross(b - a, c - a)); }

// Barycentric weight of corner a of triangle (a, b, c) at p, and whether p lies in the triangle's
// plane and inside it (tolerances for float rounding of p).
bool weight_in(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, double& wa) {
  const glm::dvec3 n = glm::cross(b - a, c - a);
  const double len = glm::length(n);
  if (std::abs(glm::dot(p - a, n / len)) > 1e-5) return false;
  wa = glm::dot(glm::cross(c - b, p - b), n) / (len * len);
  const double wb = glm::dot(glm::cross(a - c, p - c), n) / (len * len);
  return wa >= -1e-5 && wb >= -1e-5 && wa + wb <= 1.0 + 1e-5;
}

}  // namespace

TEST_CASE("vertex footprint: hat-weighted points of the one-ring (triangle shares, Beta(2,2) weight, centroid)", "[footprint]") {
  const mesh::Mesh m = fan();
  const mesh::VertexFootprints footprints(m);
  std::vector<glm::dvec3> p(m.positions.begin(), m.positions.end());
  const int tri[3][3] = {{0, 1, 2}, {0, 2, 3}, {0, 4, 1}};  // each with vertex 0 first, same orientation
  double areas[3], total = 0.0;
  glm::dvec3 centroid(0.0);
  for (int t = 0; t < 3; ++t) {
    areas[t] = area(p[tri[t][0]], p[tri[t][1]], p[tri[t][2]]);
    total += areas[t];
    centroid += areas[t] * (2.0 * p[tri[t][0]] + p[tri[t][1]] + p[tri[t][2]]) / 4.0;
  }
  centroid /= total;
  CHECK(footprints.ring_area(0) == Approx(total).epsilon(1e-9));

  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const int n = 400000;
  int in[3] = {0, 0, 0}, below_quarter = 0;
  double sum_b = 0.0, sum_b2 = 0.0;
  glm::dvec3 mean(0.0);
  for (int i = 0; i < n; ++i) {
    const glm::dvec3 q(footprints.point(0, u(rng), u(rng)));
    mean += q / static_cast<double>(n);
    int found = -1;
    double b = 0.0;
    for (int t = 0; t < 3 && found < 0; ++t)
      if (weight_in(q, p[tri[t][0]], p[tri[t][1]], p[tri[t][2]], b)) found = t;
    REQUIRE(found >= 0);
    ++in[found];
    sum_b += b;
    sum_b2 += b * b;
    below_quarter += b < 0.25;
  }
  for (int t = 0; t < 3; ++t) {
    const double share = areas[t] / total, sigma = std::sqrt(share * (1 - share) / n);
    CHECK(std::abs(in[t] / double(n) - share) < 5 * sigma);
  }
  CHECK(sum_b / n == Approx(0.5).margin(0.002));
  CHECK(sum_b2 / n == Approx(0.3).margin(0.002));
  CHECK(below_quarter / double(n) == Approx(5.0 / 32.0).margin(0.003));
  CHECK(glm::length(mean - centroid) < 0.01);
}

TEST_CASE("vertex footprint: a vertex on no triangle is its own footprint - Beta(2,2) quantile", "[footprint]") {
  const mesh::Mesh m = fan();
  const mesh::VertexFootprints footprints(m);
  CHECK(footprints.ring_area(5) == 0.0);
  const glm::vec3 q = footprints.point(5, 0.3, 0.6);
  CHECK(q == m.positions[5]);
  for (double x : {0.0, 0.05, 0.3, 0.5, 0.77, 1.0}) {
    const double cdf = 3 * x * x - 2 * x * x * x;  // Beta(2, 2) distribution function
    CHECK(mesh::beta22_quantile(cdf) == Approx(x).margin(1e-12));
  }
}

TEST_CASE("vertex footprint: copies of a smooth vertex (a UV seam) share one one-ring - a hard edge does not", "[footprint]") {
  // The fan's vertex 0 split in two along a seam: triangle 0 keeps vertex 0, triangles 1 and 2 use its
  // copy 6 (same position, same normal). Copy 7 has the position but another normal (a hard edge) and
  // one triangle of its own.
  mesh::Mesh m = fan();
  m.positions.push_back(m.positions[0]);
  m.normals.push_back(m.normals[0]);
  m.positions.push_back(m.positions[0]);
  m.normals.push_back(glm::vec3(1, 0, 0));
  m.indices = {0, 1, 2, 6, 2, 3, 4, 1, 6, 7, 3, 4};
  const mesh::VertexFootprints footprints(m);
  const double whole = area(glm::dvec3(m.positions[0]), glm::dvec3(m.positions[1]), glm::dvec3(m.positions[2])) +
                       area(glm::dvec3(m.positions[0]), glm::dvec3(m.positions[2]), glm::dvec3(m.positions[3])) +
                       area(glm::dvec3(m.positions[4]), glm::dvec3(m.positions[1]), glm::dvec3(m.positions[0]));
  CHECK(footprints.ring_area(0) == Approx(whole).epsilon(1e-9));
  CHECK(footprints.ring_area(6) == Approx(whole).epsilon(1e-9));
  CHECK(footprints.ring_area(7) == Approx(area(glm::dvec3(m.positions[0]), glm::dvec3(m.positions[3]), glm::dvec3(m.positions[4])))
                                       .epsilon(1e-9));
  // Both copies draw from all three triangles: the first triangle's share of points is its area share.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const glm::dvec3 p0(m.positions[0]), p1(m.positions[1]), p2(m.positions[2]);
  const double share = area(p0, p1, p2) / whole;
  for (std::uint32_t copy : {0u, 6u}) {
    const int n = 100000;
    int in_first = 0;
    double b = 0.0;
    for (int i = 0; i < n; ++i) in_first += weight_in(glm::dvec3(footprints.point(copy, u(rng), u(rng))), p0, p1, p2, b);
    CHECK(std::abs(in_first / double(n) - share) < 5 * std::sqrt(share * (1 - share) / n));
  }
}
