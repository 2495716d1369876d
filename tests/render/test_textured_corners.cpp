// The draw vertices of a textured mesh's indexed draw (render/textured_corners.h) against a brute-force
// count of the distinct (vertex, UV bits, material) triples, on a real third-party asset and on corners
// that differ in one of the three only.
#include <catch2/catch.hpp>

#include <cstring>
#include <set>
#include <tuple>

#include "mesh/mesh.h"
#include "render/textured_corners.h"

using namespace prt;

namespace {

using Key = std::tuple<std::uint32_t, std::uint32_t, std::uint32_t, std::uint32_t>;

Key corner_key(const mesh::Mesh& m, std::size_t c) {
  std::uint32_t u, v;
  std::memcpy(&u, &m.base_color_uv[c].x, 4);
  std::memcpy(&v, &m.base_color_uv[c].y, 4);
  return {m.indices[c], u, v, m.triangle_material[c / 3]};
}

// Every corner reads through its draw vertex exactly the triple it has; draw vertices are numbered in
// the order of their first corners; as many as the distinct triples (a set, not textured_corners' hash).
void check_corners(const mesh::Mesh& m) {
  const render::TexturedCorners t = render::textured_corners(m);
  REQUIRE(t.draw_vertex.size() == m.indices.size());
  std::set<Key> distinct;
  for (std::size_t c = 0; c < m.indices.size(); ++c) distinct.insert(corner_key(m, c));
  CHECK(t.first_corner.size() == distinct.size());
  for (std::size_t d = 1; d < t.first_corner.size(); ++d) CHECK(t.first_corner[d - 1] < t.first_corner[d]);
  for (std::size_t c = 0; c < m.indices.size(); ++c) {
    REQUIRE(t.draw_vertex[c] < t.first_corner.size());
    const std::uint32_t first = t.first_corner[t.draw_vertex[c]];
    CHECK(first <= c);
    CHECK(corner_key(m, first) == corner_key(m, c));
  }
}

}  // namespace

// BoxTextured (Khronos glTF sample, CC-BY 4.0, tests/data/README.md): 24 vertices, 12 triangles, one
// material; every corner of a vertex has that vertex's UV, so 24 draw vertices for 36 corners.
TEST_CASE("textured_corners shares a draw vertex among a real asset's corners of one vertex, UV and material",
          "[render][texture]") {
  const mesh::Mesh m = mesh::load_mesh(std::string(PRT_SOURCE_DIR) + "/tests/data/BoxTextured/BoxTextured.gltf", nullptr, true);
  REQUIRE(m.textured());
  check_corners(m);
  CHECK(render::textured_corners(m).first_corner.size() == 24);
}

// Two triangles over one quad's vertices: corners of a shared vertex differ in UV (a seam), in material,
// in the sign of a zero UV (-0 and +0: different bits), or in nothing.
TEST_CASE("textured_corners keeps corners apart that differ in UV bits or material", "[render][texture]") {
  mesh::Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  m.indices = {0, 1, 2, 0, 2, 3, 0, 1, 2};
  m.triangle_material = {0, 0, 1};
  m.base_color_uv = {{0.0f, 0.0f}, {1, 0}, {1, 1},    // triangle 0
                     {-0.0f, 0.0f}, {1, 1}, {0, 1},   // vertex 0 at -0: apart; vertex 2 as triangle 0: shared
                     {0.0f, 0.0f}, {1, 0}, {1, 1}};   // triangle 0's UVs, another material: apart
  check_corners(m);
  const render::TexturedCorners t = render::textured_corners(m);
  CHECK(t.first_corner.size() == 8);
  CHECK(t.draw_vertex[4] == t.draw_vertex[2]);
  CHECK(t.draw_vertex[3] != t.draw_vertex[0]);
  CHECK(t.draw_vertex[6] != t.draw_vertex[0]);
}
