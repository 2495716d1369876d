// Format-independent parts: fingerprints, area-weighted normals, degenerate triangles, bounds,
// format detection, garbled OBJ input.
#include <cmath>
#include <random>
#include <sstream>

#include <catch2/catch.hpp>
#include <glm/geometric.hpp>

#include "mesh/mesh.h"
#include "mesh_test_util.h"

using namespace prt::mesh;
using namespace prt::mesh::test;

namespace {

/// FNV-1a 64 written out independently of the library.
std::uint64_t fnv1a(const std::vector<std::uint8_t>& bytes) {
  std::uint64_t h = 14695981039346656037ull;
  for (std::uint8_t b : bytes) {
    h ^= b;
    h *= 1099511628211ull;
  }
  return h;
}

/// A UV sphere of radius `r` with `rings` latitude bands and `segments` longitude segments, welded
/// (one vertex per pole), outward CCW.
Mesh uv_sphere(float r, int rings, int segments) {
  Mesh m;
  const double pi = 3.14159265358979323846;
  m.positions.push_back({0, r, 0});
  for (int i = 1; i < rings; ++i) {
    const double theta = pi * i / rings;
    for (int j = 0; j < segments; ++j) {
      const double phi = 2 * pi * j / segments;
      m.positions.emplace_back(r * std::sin(theta) * std::cos(phi), r * std::cos(theta),
                               r * std::sin(theta) * std::sin(phi));
    }
  }
  m.positions.push_back({0, -r, 0});
  const auto ring = [&](int i, int j) { return std::uint32_t(1 + (i - 1) * segments + (j % segments)); };
  const std::uint32_t south = std::uint32_t(m.positions.size() - 1);
  for (int j = 0; j < segments; ++j) {
    m.indices.insert(m.indices.end(), {0, ring(1, j + 1), ring(1, j)});
    for (int i = 1; i + 1 < rings; ++i)
      m.indices.insert(m.indices.end(), {ring(i, j), ring(i, j + 1), ring(i + 1, j + 1), ring(i, j), ring(i + 1, j + 1),
                                         ring(i + 1, j)});
    m.indices.insert(m.indices.end(), {ring(rings - 1, j), ring(rings - 1, j + 1), south});
  }
  return m;
}

}  // namespace

TEST_CASE("fingerprint is FNV-1a 64 over counts and position bits and indices (little-endian)", "[mesh][fingerprint]") {
  // The reference FNV-1a itself: the published test vector for "a".
  REQUIRE(fnv1a({'a'}) == 0xaf63dc4c8601ec8cull);

  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  m.indices = {0, 1, 2};
  // The byte stream spelled out: u64 3, nine floats (1.0f = 0x3f800000), u64 3, u32 0, 1, 2.
  std::vector<std::uint8_t> bytes = {3, 0, 0, 0, 0, 0, 0, 0};
  const std::uint32_t floats[9] = {0, 0, 0, 0x3f800000, 0, 0, 0, 0x3f800000, 0};
  for (std::uint32_t f : floats)
    for (int k = 0; k < 4; ++k) bytes.push_back(std::uint8_t(f >> (8 * k)));
  for (std::uint8_t b : {3, 0, 0, 0, 0, 0, 0, 0}) bytes.push_back(b);
  for (std::uint32_t i : {0u, 1u, 2u})
    for (int k = 0; k < 4; ++k) bytes.push_back(std::uint8_t(i >> (8 * k)));
  CHECK(fingerprint(m) == fnv1a(bytes));
  CHECK(fingerprint(m) == 0xb0049a912dd29696ull);  // computed separately (Python struct + FNV-1a)

  // Stable: normals and albedo do not enter; the same data gives the same value.
  Mesh copy = m;
  copy.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  copy.albedo = {{1, 0, 0}, {1, 0, 0}, {1, 0, 0}};
  CHECK(fingerprint(copy) == fingerprint(m));
  // One position bit, the sign of a zero, or an index order change it.
  for (int c = 0; c < 3; ++c) {
    Mesh changed = m;
    std::uint32_t bits = float_bits(changed.positions[1][c]) ^ 1u;
    std::memcpy(&changed.positions[1][c], &bits, 4);
    CHECK(fingerprint(changed) != fingerprint(m));
  }
  Mesh negative_zero = m;
  negative_zero.positions[0].x = -0.0f;
  CHECK(fingerprint(negative_zero) != fingerprint(m));
  Mesh rotated = m;
  rotated.indices = {1, 2, 0};
  CHECK(fingerprint(rotated) != fingerprint(m));
}

TEST_CASE("area-weighted normals of a sphere point outward close to the radial direction", "[mesh][normals]") {
  // On a UV sphere the residual comes from each quad's diagonal split and the unequal areas of the
  // bands around a vertex; it shrinks with the band spacing (7.5 degrees, then 3.75).
  auto worst_angle_degrees = [](const Mesh& sphere) {
    const std::vector<glm::vec3> normals = area_weighted_normals(sphere.positions, sphere.indices);
    double worst = 0.0;
    for (std::size_t i = 0; i < normals.size(); ++i) {
      const glm::dvec3 n(normals[i]);
      CHECK(glm::length(n) == Approx(1.0).margin(1e-6));
      const glm::dvec3 radial = glm::normalize(glm::dvec3(sphere.positions[i]));
      worst = std::max(worst, std::acos(std::min(1.0, glm::dot(n, radial))) * 180.0 / 3.14159265358979);
    }
    return worst;
  };
  const double coarse = worst_angle_degrees(uv_sphere(2.0f, 24, 48));
  const double fine = worst_angle_degrees(uv_sphere(2.0f, 48, 96));
  INFO("worst angles " << coarse << " and " << fine << " degrees");
  CHECK(coarse < 1.5);
  CHECK(fine < 0.6 * coarse);
  // A flat triangle's vertices get its exact normal; a vertex of no triangle gets +Y.
  const std::vector<glm::vec3> lonely = area_weighted_normals({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {5, 5, 5}}, {0, 1, 2});
  CHECK(lonely[0] == glm::vec3(0, 0, 1));
  CHECK(lonely[3] == glm::vec3(0, 1, 0));
}

TEST_CASE("degenerate triangles are skipped and counted and bounds are exact", "[mesh][degenerate]") {
  CHECK(is_degenerate({0, 0, 0}, {1, 0, 0}, {2, 0, 0}));
  CHECK(is_degenerate({1, 1, 1}, {1, 1, 1}, {1, 1, 1}));
  CHECK_FALSE(is_degenerate({0, 0, 0}, {1, 0, 0}, {0, 1e-6f, 0}));
  CHECK_FALSE(is_degenerate({0, 0, 0}, {1e-20f, 0, 0}, {0, 1e-20f, 0}));  // tiny but not degenerate

  const std::string path = write_temp("degenerate.obj",
                                      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nv 1 1 1\nv 1 1 1\n"
                                      "f 1 2 3\n"    // kept
                                      "f 1 2 4\n"    // collinear
                                      "f 1 1 3\n"    // repeated index
                                      "f 5 6 5\n"    // repeated index
                                      "f 5 6 1\n"    // distinct indices, coincident points
                                      "f 1 3 4\n");  // kept
  LoadReport report;
  const Mesh mesh = load_mesh(path, &report, true);
  CHECK(report.skipped_degenerate == 4);
  CHECK(mesh.indices == std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3});
  CHECK(mesh.vertex_count() == 6);  // vertices are never dropped
  CHECK(report.notes[0] == "skipped 4 degenerate triangles (repeated vertex, zero area, or fewer than 3 vertices)");
  const Bounds box = bounds(mesh);
  CHECK(box.lo == glm::vec3(0, 0, 0));
  CHECK(box.hi == glm::vec3(2, 1, 1));
  CHECK(box.diagonal() == Approx(std::sqrt(6.0)));
}

TEST_CASE("format detection by extension and content and unreadable files", "[mesh][errors]") {
  const std::string stl = write_temp("model.stl", "solid x\nendsolid x\n");
  CHECK(error_of([&] { load_mesh(stl, nullptr, true); }) ==
        stl + ": unsupported mesh format \".stl\" (prt reads .obj, .ply, .gltf and .glb)");
  const std::string none = write_temp("model", "v 0 0 0\n");
  CHECK(error_of([&] { load_mesh(none, nullptr, true); }) ==
        none + ": unsupported mesh format \"\" (prt reads .obj, .ply, .gltf and .glb)");
  const std::string missing = temp_path("missing.obj");
  CHECK(error_of([&] { load_mesh(missing, nullptr, true); }) == missing + ": cannot open: No such file or directory");
  const std::string empty = write_temp("empty.ply", "");
  CHECK(error_of([&] { load_mesh(empty, nullptr, true); }) == empty + ": file is empty");
  CHECK(error_of([&] { load_mesh(temp_dir() + "/", nullptr, true); }) != "");
  // The extension is case-insensitive.
  const std::string upper = write_temp("UPPER.OBJ", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  CHECK(load_mesh(upper, nullptr, true).triangle_count() == 1);
}

TEST_CASE("Garbled OBJ files load or fail with prt::Error and never crash", "[mesh][obj]") {
  write_temp("fuzz.mtl", "newmtl a\nKd 0.5 0.5 0.5\n");
  const std::string original =
      "mtllib fuzz.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nvt 0 0\nusemtl a\n"
      "f 1/1/1 2/1/1 3/1/1 4/1/1\nf -4 -3 -1\ng group\ns 1\nl 1 2\n";
  std::mt19937 rng(99);
  const char alphabet[] = "0123456789 -/\n.fvnteE#x\0";
  for (int trial = 0; trial < 400; ++trial) {
    std::string bytes = original;
    const int edits = 1 + int(rng() % 4);
    for (int k = 0; k < edits; ++k) bytes[rng() % bytes.size()] = alphabet[rng() % (sizeof alphabet - 1)];
    try {
      load_mesh(write_temp("fuzz.obj", bytes), nullptr, true);
    } catch (const prt::Error&) {
    }
  }
  SUCCEED("no crash and no exception other than prt::Error");
}

TEST_CASE("the shipped meshes load: outward winding and unit radius and Y up", "[mesh][assets]") {
  struct Asset {
    const char* file;
    std::size_t vertices, triangles;
  };
  for (const Asset& asset : {Asset{"guardian_lion_10k.ply", 10000, 19994}, Asset{"armadillo.ply", 26002, 52000}}) {
    INFO(asset.file);
    LoadReport report;
    const Mesh mesh = load_mesh(std::string(PRT_SOURCE_DIR) + "/assets/meshes/" + asset.file, &report, true);
    CHECK(mesh.vertex_count() == asset.vertices);
    CHECK(mesh.triangle_count() == asset.triangles);
    CHECK(report.skipped_degenerate == 0);
    CHECK(report.normals_computed);
    double volume = 0.0, farthest = 0.0;
    for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
      const glm::dvec3 a(mesh.positions[mesh.indices[t]]), b(mesh.positions[mesh.indices[t + 1]]),
          c(mesh.positions[mesh.indices[t + 2]]);
      volume += glm::dot(a, glm::cross(b, c)) / 6.0;
    }
    for (const glm::vec3& p : mesh.positions) farthest = std::max(farthest, double(glm::length(p)));
    CHECK(volume > 0.2);  // outward winding: a unit-radius figure encloses a good part of the ball
    CHECK(farthest == Approx(1.0).margin(1e-6));
    const Bounds box = bounds(mesh);
    CHECK(box.hi.y - box.lo.y > box.hi.x - box.lo.x);  // standing figures: tallest along +Y
    // Centred: the bounding box is symmetric about the origin.
    for (int c = 0; c < 3; ++c) CHECK(box.lo[c] + box.hi[c] == Approx(0.0).margin(1e-6));
  }
}
