// The true-surface rule (trace/true_surface.h, docs/conventions.md "Directions below the true surface")
// in the texel passes: a texel sample lies on one triangle, so its rays below that triangle's plane carry
// no light. On a convex mesh with smooth normals tilted 20+ degrees from their faces (a coarse UV
// sphere, each triangle its own lightmap chart) an interreflected texel bake must equal the shadowed
// one. NOISE: both bakes trace the same rays (same seed) and the bounce passes of a convex mesh add
// exactly 0; the bound, 1e-5 of the largest coefficient, allows float rounding only (the old error,
// texel rays below their triangle gathering its own light, was about 2%).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "bake/bake.h"
#include "lightmap/texel_bake.h"
#include "support/shapes.h"

using namespace prt;

TEST_CASE("true surface: an interreflected texel bake of a convex mesh equals its shadowed bake", "[lightmap]") {
  mesh::Mesh sphere = test::uv_sphere(6, 8);
  REQUIRE(test::max_normal_tilt(sphere) >= 20.0);
  test::add_triangle_charts(sphere);
  lightmap::LightmapOptions lightmap;
  lightmap.width = lightmap.height = 96;
  bake::BakeOptions o;
  o.kind = transfer::Kind::shadowed;
  o.bands = 3;
  o.samples = 128;
  o.albedo = glm::vec3(0.9f);
  o.seed = 3;
  o.threads = 2;
  const transfer::TransferData shadowed = lightmap::bake_lightmap(sphere, o, lightmap);
  o.kind = transfer::Kind::interreflected;
  o.bounces = 1;
  lightmap::LightmapReport report;
  const transfer::TransferData bounced = lightmap::bake_lightmap(sphere, o, lightmap, &report);
  REQUIRE(report.covered > 2000);
  REQUIRE(shadowed.values.size() == bounced.values.size());
  double largest = 0.0, worst = 0.0, dc_shadowed = 0.0, dc_bounced = 0.0;
  for (std::size_t i = 0; i < shadowed.values.size(); ++i) {
    largest = std::max(largest, std::abs(double(shadowed.values[i])));
    worst = std::max(worst, std::abs(double(bounced.values[i]) - shadowed.values[i]));
    if (i % 9 == 0) {
      dc_shadowed += shadowed.values[i];
      dc_bounced += bounced.values[i];
    }
  }
  INFO(report.covered << " texels: interreflected against shadowed, mean l = 0 change "
                      << (dc_bounced - dc_shadowed) / dc_shadowed << ", worst coefficient " << worst << " of " << largest);
  CHECK(worst <= 1e-5 * largest);
}
