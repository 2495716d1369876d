// BakeOptions::footprint against brute-force quadrature in two scenes on a unit grid:
// - a V-shaped groove (a floor y = 0 and a wall leaning over it at 45 degrees, meeting along the x axis),
//   whose crease vertices have the bisector normal: rays below a footprint point's own face are blocked;
// - small square overhangs (0.2 wide, 0.05 above the floor) over five floor vertices, like the folds of a
//   scanned statue: each darkens its vertex far more than the surface that the vertex's value covers.
// Truth: the cosine-weighted visible fraction about the vertex normal, averaged over the vertex's
// one-ring with its hat weight (footprint area) or at the vertex alone (footprint vertex), by midpoint
// quadrature over sub-triangles and a stratified grid of directions, with visibility from ray-rectangle
// tests written here (not Embree, not the bake's footprint sampler).
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <vector>

#include <glm/geometric.hpp>

#include "bake/bake.h"
#include "light/disc.h"
#include "mesh/vertex_footprint.h"
#include "shade/disc_direct.h"
#include "shade/surface_albedo.h"
#include "support/shapes.h"
#include "trace/scene.h"

using namespace prt;

namespace {

// Whether the ray from q toward w escapes, with q on the floor, the wall or both (the groove's crease).
using Escapes = std::function<bool(const glm::dvec3& q, const glm::dvec3& w, bool on_floor, bool on_wall)>;

constexpr int kHalf = 8;  // the floor spans x in [-8, 8], z in [0, 8]; the wall x in [-8, 8], 8 units up its slope
constexpr double kY00 = 0.28209479177387814;
const double kAngle = M_PI / 4;  // between the floor (toward +z) and the wall
const glm::dvec3 kUp(0, std::sin(kAngle), std::cos(kAngle));          // along the wall, away from the crease
const glm::dvec3 kWallNormal(0, -std::cos(kAngle), std::sin(kAngle));  // the wall's front, facing the floor
const glm::dvec3 kFloorNormal(0, 1, 0);

int floor_vertex(int i, int r) { return r * (2 * kHalf + 1) + i; }  // r = 0: the crease
int wall_vertex(int i, int r) { return r == 0 ? floor_vertex(i, 0) : (kHalf + r) * (2 * kHalf + 1) + i; }

mesh::Mesh corner() {
  mesh::Mesh m;
  const int columns = 2 * kHalf + 1;
  const glm::vec3 bisector(glm::normalize(kFloorNormal + kWallNormal));
  for (int r = 0; r <= kHalf; ++r)
    for (int i = 0; i < columns; ++i) {
      m.positions.emplace_back(i - kHalf, 0, r);
      m.normals.push_back(r == 0 ? bisector : glm::vec3(0, 1, 0));
    }
  for (int r = 1; r <= kHalf; ++r)
    for (int i = 0; i < columns; ++i) {
      m.positions.push_back(glm::vec3(glm::dvec3(i - kHalf, 0, 0) + double(r) * kUp));
      m.normals.push_back(glm::vec3(kWallNormal));
    }
  auto quad = [&m](int a, int b, int c, int d) {  // counter-clockwise seen from the front
    m.indices.insert(m.indices.end(), {std::uint32_t(a), std::uint32_t(b), std::uint32_t(c), std::uint32_t(a),
                                       std::uint32_t(c), std::uint32_t(d)});
  };
  for (int r = 0; r < kHalf; ++r)
    for (int i = 0; i + 1 < columns; ++i) {
      quad(floor_vertex(i, r), floor_vertex(i, r + 1), floor_vertex(i + 1, r + 1), floor_vertex(i + 1, r));
      quad(wall_vertex(i, r), wall_vertex(i + 1, r), wall_vertex(i + 1, r + 1), wall_vertex(i, r + 1));
    }
  return m;
}

// Whether the ray from q (on the floor, on the wall, or on the crease: both) toward w escapes. Both
// planes pass through the x axis; each blocks the rays that reach its rectangle.
bool escapes_groove(const glm::dvec3& q, const glm::dvec3& w, bool on_floor, bool on_wall) {
  if ((on_floor && glm::dot(w, kFloorNormal) < 0) || (on_wall && glm::dot(w, kWallNormal) < 0)) return false;  // into itself
  if (!on_wall && glm::dot(w, kWallNormal) < 0) {  // toward the wall's plane from its front
    const double t = -glm::dot(q, kWallNormal) / glm::dot(w, kWallNormal);
    const glm::dvec3 h = q + t * w;
    const double up = glm::dot(h, kUp);
    if (up >= 0 && up <= kHalf && std::abs(h.x) <= kHalf) return false;
  }
  if (!on_floor && glm::dot(w, kFloorNormal) < 0) {  // toward the floor's plane from above
    const double t = -q.y / w.y;
    const glm::dvec3 h = q + t * w;
    if (h.z >= 0 && h.z <= kHalf && std::abs(h.x) <= kHalf) return false;
  }
  return true;
}

// Cosine-weighted visible fraction about n at q: a 64 x 64 stratified grid (cell centres) mapped to the
// cosine-weighted hemisphere (r = sqrt(u), phi = 2 pi v).
double visible_fraction(const Escapes& escapes, const glm::dvec3& q, const glm::dvec3& n, bool on_floor, bool on_wall) {
  const glm::dvec3 t = glm::normalize(glm::cross(glm::dvec3(1, 0, 0), n)), b = glm::cross(n, t);
  constexpr int kGrid = 64;
  int visible = 0;
  for (int i = 0; i < kGrid; ++i)
    for (int j = 0; j < kGrid; ++j) {
      const double u = (i + 0.5) / kGrid, v = (j + 0.5) / kGrid, r = std::sqrt(u), phi = 2 * M_PI * v;
      const glm::dvec3 w = r * std::cos(phi) * t + r * std::sin(phi) * b + std::sqrt(1 - u) * n;
      visible += escapes(q, w, on_floor, on_wall);
    }
  return visible / double(kGrid * kGrid);
}

// The hat-weighted mean of f(q, on_floor, on_wall) over vertex c's one-ring: each triangle with c cut
// into cuts x cuts sub-triangles, each weighted by its area times c's barycentric weight at its centroid.
template <class F>
double hat_average(const mesh::Mesh& m, std::uint32_t c, int cuts, const F& f) {
  const int kCuts = cuts;
  double sum = 0.0, weight = 0.0;
  for (std::size_t t = 0; t < m.indices.size(); t += 3) {
    int k = 0;
    while (k < 3 && m.indices[t + k] != c) ++k;
    if (k == 3) continue;
    const glm::dvec3 a(m.positions[c]), b(m.positions[m.indices[t + (k + 1) % 3]]), d(m.positions[m.indices[t + (k + 2) % 3]]);
    const bool on_floor = a.y == 0 && b.y == 0 && d.y == 0, on_wall = !on_floor;  // footprints touch no overhang
    for (int i = 0; i < kCuts; ++i)
      for (int j = 0; i + j < kCuts; ++j)
        for (int up = 0; up < 2; ++up) {
          if (up && i + j + 1 >= kCuts) continue;
          // Centroid of the sub-triangle in (b, d) barycentric steps; upward and downward ones have equal area.
          const double sb = (i + (up ? 2.0 : 1.0) / 3.0) / kCuts, sd = (j + (up ? 2.0 : 1.0) / 3.0) / kCuts;
          const double hat = 1.0 - sb - sd;
          const glm::dvec3 q = a + sb * (b - a) + sd * (d - a);
          sum += hat * f(q, on_floor, on_wall);
          weight += hat;
        }
  }
  return sum / weight;
}

// The hat-weighted mean of visible_fraction over vertex c's one-ring (12 x 12 cuts).
double footprint_truth(const Escapes& escapes, const mesh::Mesh& m, std::uint32_t c, const glm::dvec3& n) {
  return hat_average(m, c, 12, [&](const glm::dvec3& q, bool on_floor, bool on_wall) {
    return visible_fraction(escapes, q, n, on_floor, on_wall);
  });
}

double baked_fraction(const mesh::Mesh& m, mesh::Footprint footprint, std::uint32_t v, transfer::TransferData* cache) {
  if (cache->values.empty()) {
    bake::BakeOptions o;
    o.kind = transfer::Kind::shadowed;
    o.bands = 3;
    o.samples = 16384;
    o.albedo = glm::vec3(1.0f);
    o.footprint = footprint;
    *cache = bake::bake(m, o);
  }
  return cache->values[v * cache->header.values_per_vertex()] / kY00;
}

}  // namespace

TEST_CASE("bake footprint: crease vertices of a 45-degree groove see the hat-weighted visibility of their one-ring (area) or their own (vertex)",
          "[bake][footprint]") {
  const mesh::Mesh m = corner();
  const glm::dvec3 n = glm::normalize(kFloorNormal + kWallNormal);
  const double at_vertex = visible_fraction(escapes_groove, glm::dvec3(0, 0, 0), n, true, true);
  transfer::TransferData area, vertex;
  double truth_sum = 0.0, area_sum = 0.0, vertex_sum = 0.0;
  int count = 0;
  for (int i = kHalf - 3; i <= kHalf + 3; ++i) {  // crease vertices at x = -3 .. 3, away from the ends
    const auto v = static_cast<std::uint32_t>(floor_vertex(i, 0));
    const double truth = footprint_truth(escapes_groove, m, v, n);
    const double a = baked_fraction(m, mesh::Footprint::area, v, &area);
    const double p = baked_fraction(m, mesh::Footprint::vertex, v, &vertex);
    INFO("x = " << i - kHalf << ": footprint truth " << truth << ", baked " << a << "; at the vertex " << at_vertex << ", baked " << p);
    CHECK(std::abs(a - truth) < 0.03);
    CHECK(std::abs(p - at_vertex) < 0.03);
    truth_sum += truth;
    area_sum += a;
    vertex_sum += p;
    ++count;
  }
  // Over the seven vertices: within 0.005 of the truth, which is 0.016 above the vertex's own fraction.
  CHECK(area_sum / count == Approx(truth_sum / count).margin(0.005));
  CHECK(vertex_sum / count == Approx(at_vertex).margin(0.005));
}

namespace {

constexpr double kLidHalf = 0.1, kLidHeight = 0.05;
const double kLidX[5] = {-6, -3, 0, 3, 6};

// A floor x in [-8, 8], z in [-2, 2] (normal +y) and the five lids (test::floor_with_lids).
mesh::Mesh floor_with_lids() {
  return test::floor_with_lids(kHalf, std::vector<double>(std::begin(kLidX), std::end(kLidX)), kLidHalf, kLidHeight);
}

bool escapes_lids(const glm::dvec3& q, const glm::dvec3& w, bool, bool) {
  if (w.y <= 0) return false;
  const double t = (kLidHeight - q.y) / w.y;
  const glm::dvec3 h = q + t * w;
  for (double x : kLidX)
    if (std::abs(h.x - x) <= kLidHalf && std::abs(h.z) <= kLidHalf) return false;
  return true;
}

}  // namespace

TEST_CASE("bake footprint: a vertex under a small overhang stores the visibility of the surface it covers (area), not its own (vertex)",
          "[bake][footprint]") {
  const mesh::Mesh m = floor_with_lids();
  const glm::dvec3 n(0, 1, 0);
  const double at_vertex = visible_fraction(escapes_lids, glm::dvec3(0, 0, 0), n, true, false);
  transfer::TransferData area, vertex;
  double truth_sum = 0.0, area_sum = 0.0, vertex_sum = 0.0;
  for (double x : kLidX) {
    const auto v = std::uint32_t(2 * (2 * kHalf + 1) + int(x) + kHalf);  // floor vertex (x, 0, 0)
    REQUIRE(m.positions[v] == glm::vec3(float(x), 0.0f, 0.0f));
    const double truth = footprint_truth(escapes_lids, m, v, n);
    const double a = baked_fraction(m, mesh::Footprint::area, v, &area);
    const double p = baked_fraction(m, mesh::Footprint::vertex, v, &vertex);
    INFO("x = " << x << ": footprint truth " << truth << ", baked " << a << "; at the vertex " << at_vertex << ", baked " << p);
    CHECK(std::abs(a - truth) < 0.05);
    CHECK(std::abs(p - at_vertex) < 0.02);
    truth_sum += truth;
    area_sum += a;
    vertex_sum += p;
  }
  CHECK(area_sum / 5 == Approx(truth_sum / 5).margin(0.02));
  CHECK(vertex_sum / 5 == Approx(at_vertex).margin(0.01));
  CHECK(truth_sum / 5 > at_vertex + 0.3);  // the overhang darkens the vertex, not its footprint
}

TEST_CASE("disc shading of an area bake: the sun's shadow rays leave from the footprint too", "[bake][footprint][sun]") {
  // A small sun straight above the lids: each lid's vertex is in full shadow, its footprint only where
  // the lid is above it (the penumbra, 0.05 tan(0.5 deg) wide, is far below the quadrature's cells).
  const mesh::Mesh m = floor_with_lids();
  const trace::Scene scene(m, trace::SceneOptions{1, true});
  light::Disc sun;
  sun.direction = glm::dvec3(0, 1, 0);
  sun.irradiance = glm::dvec3(M_PI);  // (albedo / pi) E (n . d) = 1 where lit
  sun.angular_radius = 0.5 * M_PI / 180;
  const std::vector<glm::vec3> albedo(m.positions.size(), glm::vec3(1.0f));
  const mesh::VertexFootprints footprints(m);
  shade::DiscShadingOptions at_vertex, over_area;
  at_vertex.samples = over_area.samples = 1024;
  over_area.footprints = &footprints;
  const std::vector<glm::vec3> point = shade::disc_direct_diffuse(m, albedo, {sun}, &scene, at_vertex);
  const std::vector<glm::vec3> area = shade::disc_direct_diffuse(m, albedo, {sun}, &scene, over_area);
  double truth_sum = 0.0, area_sum = 0.0;
  for (double x : kLidX) {
    const auto v = std::uint32_t(2 * (2 * kHalf + 1) + int(x) + kHalf);
    const double truth = hat_average(m, v, 48, [](const glm::dvec3& q, bool, bool) {
      return escapes_lids(q, glm::dvec3(0, 1, 0), true, false) ? 1.0 : 0.0;
    });
    INFO("x = " << x << ": lit fraction of the footprint " << truth << ", area " << area[v].r << ", at the vertex " << point[v].r);
    CHECK(point[v].r == 0.0f);
    CHECK(std::abs(area[v].r - truth) < 0.03);
    truth_sum += truth;
    area_sum += area[v].r;
  }
  CHECK(area_sum / 5 == Approx(truth_sum / 5).margin(0.01));
  CHECK(truth_sum / 5 > 0.9);  // against 0 at the vertex itself
}

TEST_CASE("prt shade reads the footprint a transfer was baked with - a bad entry is an error naming the file", "[bake][footprint]") {
  transfer::Header h;
  h.parameters_json = "{}";
  CHECK(shade::baked_footprint(h, "t.prt") == mesh::Footprint::vertex);
  h.parameters_json = R"({"footprint":"area"})";
  CHECK(shade::baked_footprint(h, "t.prt") == mesh::Footprint::area);
  h.parameters_json = R"({"footprint":"vertex"})";
  CHECK(shade::baked_footprint(h, "t.prt") == mesh::Footprint::vertex);
  h.parameters_json = R"({"footprint":7})";
  CHECK_THROWS_WITH(shade::baked_footprint(h, "t.prt"), Catch::Contains("t.prt") && Catch::Contains("\"footprint\" must be"));
}
