// The true-surface rule (trace/true_surface.h, docs/conventions.md "Directions below the true surface")
// in the bake's passes: on convex meshes with smooth normals tilted 20+ degrees from their faces (a
// coarse UV sphere, the convex hull of the guardian lion scan) light cannot bounce, so an
// interreflected bake must equal the shadowed bake, with vertex and area footprints; and a white
// furnace reflects 1 at the vertices and, over area footprints, the share of the lobe the rule keeps.
//
// NOISE. Both bakes trace the same rays (same seed, same sample set and frames), and the interreflected
// bake is the shadowed one plus its bounce passes: on a convex mesh every admitted ray escapes, so the
// bounce passes add exactly 0. The bound, 1e-5 of the largest coefficient, allows float rounding only;
// the old error (rays below a footprint point's face gathering the face's own light) was 2-5%.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include "bake/bake.h"
#include "brdf/brdf.h"
#include "light/disc.h"
#include "mesh/mesh.h"
#include "mesh/vertex_footprint.h"
#include "shade/disc_direct.h"
#include "trace/scene.h"
#include "support/shapes.h"

using namespace prt;

namespace {

bake::BakeOptions convex_options(transfer::Kind kind, mesh::Footprint footprint, int samples) {
  bake::BakeOptions o;
  o.kind = kind;
  o.bands = 3;
  o.samples = samples;
  o.bounces = kind == transfer::Kind::interreflected ? 1 : -1;
  o.albedo = glm::vec3(0.9f);
  o.seed = 5;
  o.threads = 2;
  o.footprint = footprint;
  return o;
}

void check_no_bounce_light(const mesh::Mesh& m, mesh::Footprint footprint, int samples) {
  const transfer::TransferData shadowed = bake::bake(m, convex_options(transfer::Kind::shadowed, footprint, samples));
  const transfer::TransferData bounced = bake::bake(m, convex_options(transfer::Kind::interreflected, footprint, samples));
  REQUIRE(shadowed.values.size() == bounced.values.size());
  double largest = 0.0, worst = 0.0, dc_shadowed = 0.0, dc_bounced = 0.0;
  const std::size_t n = 9;
  for (std::size_t i = 0; i < shadowed.values.size(); ++i) {
    largest = std::max(largest, std::abs(double(shadowed.values[i])));
    worst = std::max(worst, std::abs(double(bounced.values[i]) - shadowed.values[i]));
    if (i % n == 0) {
      dc_shadowed += shadowed.values[i];
      dc_bounced += bounced.values[i];
    }
  }
  INFO(m.vertex_count() << " vertices, footprint " << mesh::footprint_name(footprint) << ": interreflected against shadowed, "
                        << "mean l = 0 change " << (dc_bounced - dc_shadowed) / dc_shadowed << ", worst coefficient "
                        << worst << " of " << largest);
  CHECK(worst <= 1e-5 * largest);
}

}  // namespace

TEST_CASE("true surface: an interreflected bake of a convex mesh equals its shadowed bake", "[bake]") {
  const mesh::Mesh sphere = test::uv_sphere(6, 8);
  REQUIRE(test::max_normal_tilt(sphere) >= 20.0);
  const mesh::Mesh lion = mesh::load_mesh(std::string(PRT_SOURCE_DIR) + "/assets/meshes/guardian_lion_10k.ply", nullptr, true);
  const mesh::Mesh hull = test::convex_hull(lion.positions);
  REQUIRE(test::max_normal_tilt(hull) >= 20.0);
  for (mesh::Footprint footprint : {mesh::Footprint::vertex, mesh::Footprint::area}) {
    check_no_bounce_light(sphere, footprint, 512);
    check_no_bounce_light(hull, footprint, 256);
  }
}

TEST_CASE("true surface: a glossy interreflected bake of a convex mesh over area footprints equals the glossy shadowed one", "[bake]") {
  // As above for the glossy passes (matrices; same rays in both bakes, bound: float rounding only).
  const mesh::Mesh sphere = test::uv_sphere(6, 8);
  bake::BakeOptions o = convex_options(transfer::Kind::glossy_shadowed, mesh::Footprint::area, 256);
  o.brdf = brdf::parse_brdf("lambert:albedo=0.6+phong:exponent=10,ks=0.3");
  const transfer::TransferData shadowed = bake::bake(sphere, o);
  o.kind = transfer::Kind::glossy_interreflected;
  o.bounces = 1;
  const transfer::TransferData bounced = bake::bake(sphere, o);
  REQUIRE(shadowed.values.size() == bounced.values.size());
  double largest = 0.0, worst = 0.0;
  for (std::size_t i = 0; i < shadowed.values.size(); ++i) {
    largest = std::max(largest, std::abs(double(shadowed.values[i])));
    worst = std::max(worst, std::abs(double(bounced.values[i]) - shadowed.values[i]));
  }
  INFO("glossy interreflected against shadowed: worst entry " << worst << " of " << largest);
  CHECK(worst <= 1e-5 * largest);
}

TEST_CASE("true surface: a white furnace baked over area footprints keeps what the rule keeps", "[bake]") {
  // Albedo 1, uniform sky 1: radiance = 2 sqrt(pi) T_00 (bake.h). Each footprint point keeps the share
  // kappa of its vertex's cosine lobe above its own face, with or without bounces; truth per vertex:
  // the hat-weighted mean of kappa by quadrature (test::footprint_lobe_share). Noise: S = 1024 rays over
  // 64 footprint points, binomial per ray (sd about 0.006 per vertex); bound 0.02 per vertex, 0.003 on
  // the mean. At the vertices themselves (vertex footprint) the furnace reflects 1 to 1e-4 (control
  // variate: nothing is occluded).
  const mesh::Mesh sphere = test::uv_sphere(6, 8);
  for (int bounces : {0, 3}) {
    bake::BakeOptions o = convex_options(transfer::Kind::interreflected, mesh::Footprint::area, 1024);
    o.albedo = glm::vec3(1.0f);
    o.bounces = bounces;
    const transfer::TransferData t = bake::bake(sphere, o);
    o.footprint = mesh::Footprint::vertex;
    const transfer::TransferData at_vertex = bake::bake(sphere, o);
    double mean = 0.0, mean_share = 0.0;
    for (std::uint32_t v = 0; v < sphere.vertex_count(); ++v) {
      const double radiance = 2.0 * std::sqrt(M_PI) * t.values[v * 9], share = test::footprint_lobe_share(sphere, v);
      INFO("bounces " << bounces << ", vertex " << v << ": " << radiance << " against kappa " << share);
      CHECK(std::abs(radiance - share) <= 0.02);
      CHECK(2.0 * std::sqrt(M_PI) * at_vertex.values[v * 9] == Approx(1.0).margin(1e-4));
      mean += radiance / sphere.vertex_count();
      mean_share += share / sphere.vertex_count();
    }
    INFO("bounces " << bounces << ": mean radiance " << mean << " against mean kappa " << mean_share);
    CHECK(mean_share < 0.98);
    CHECK(std::abs(mean - mean_share) <= 0.003);
  }
}

TEST_CASE("true surface: the exact disc term from footprint points and from points given with their triangle's normal", "[bake]") {
  // A small sun (0.25 degrees) low over the coarse sphere, E = pi, albedo 1: a point's term is
  // (n . d) where its own triangle faces the sun (ng . d > 0; nothing else on a convex mesh can shade
  // it) and 0 elsewhere. Truth per vertex over its footprint: (n . d) times the hat-weighted share of its
  // one-ring whose triangles face the sun (area / 3 each); 1024 stratified disc rays each from its own
  // footprint point, bound 0.02 (the share's sampling noise). Points given one by one (a mesh of points,
  // as the lightmap's texels are shaded) with DiscShadingOptions::geometric_normals: exactly 0 or n . d.
  // The direct term was right before the rule too (a ray below its own triangle hits it, but for rays
  // slipping past an edge): this checks that the rule's wiring keeps it so, it shows no old error.
  const mesh::Mesh sphere = test::uv_sphere(6, 8);
  const trace::Scene scene(sphere, trace::SceneOptions{1, true});
  light::Disc sun;
  sun.direction = glm::normalize(glm::dvec3(1.0, 0.15, 0.2));
  sun.irradiance = glm::dvec3(M_PI);
  sun.angular_radius = 0.25 * M_PI / 180;
  const std::vector<glm::vec3> albedo(sphere.vertex_count(), glm::vec3(1.0f));
  const mesh::VertexFootprints footprints(sphere);
  shade::DiscShadingOptions over_area;
  over_area.samples = 1024;
  over_area.footprints = &footprints;
  const std::vector<glm::vec3> area = shade::disc_direct_diffuse(sphere, albedo, {sun}, &scene, over_area);
  int partial = 0;
  mesh::Mesh points;
  std::vector<glm::vec3> geometric_normals;
  std::vector<double> expected;
  for (std::uint32_t v = 0; v < sphere.vertex_count(); ++v) {
    const double cosine = glm::dot(glm::dvec3(sphere.normals[v]), sun.direction);
    double facing = 0.0, total = 0.0;
    for (std::size_t t : test::triangles_of(sphere, v)) {
      const std::uint32_t* tri = sphere.indices.data() + 3 * t;
      const glm::dvec3 c = test::face_cross(sphere, t), p0(sphere.positions[tri[0]]);
      total += glm::length(c);
      if (glm::dot(c, sun.direction) > 0.0) facing += glm::length(c);
      // One point per triangle corner, a third of the way to the centroid, with v's normal.
      const glm::dvec3 centroid = (p0 + glm::dvec3(sphere.positions[tri[1]]) + glm::dvec3(sphere.positions[tri[2]])) / 3.0;
      points.positions.push_back(glm::vec3((2.0 * glm::dvec3(sphere.positions[v]) + centroid) / 3.0));
      points.normals.push_back(sphere.normals[v]);
      geometric_normals.push_back(glm::vec3(glm::normalize(c)));
      expected.push_back(cosine > 0.0 && glm::dot(c, sun.direction) > 0.0 ? cosine : 0.0);
    }
    const double truth = std::max(0.0, cosine) * facing / total;
    if (truth > 0.0 && facing < total) ++partial;
    INFO("vertex " << v << ": " << area[v].r << " against " << truth);
    CHECK(std::abs(area[v].r - truth) <= 0.02);
  }
  CHECK(partial >= 4);  // vertices whose footprint the terminator crosses
  const std::vector<glm::vec3> point_albedo(points.vertex_count(), glm::vec3(1.0f));
  shade::DiscShadingOptions given;
  given.samples = 16;
  given.geometric_normals = &geometric_normals;
  const std::vector<glm::vec3> lit = shade::disc_direct_diffuse(points, point_albedo, {sun}, &scene, given);
  int blocked = 0;
  for (std::size_t k = 0; k < expected.size(); ++k) {
    INFO("point " << k << ": " << lit[k].r << " against " << expected[k]);
    CHECK(lit[k].r == Approx(expected[k]).margin(0.01));
    blocked += expected[k] == 0.0 && glm::dot(glm::dvec3(points.normals[k]), sun.direction) > 0.0;
  }
  CHECK(blocked >= 4);  // points facing the sun through their shading normal, not their triangle
}
