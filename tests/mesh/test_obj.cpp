// OBJ loading: vertex order, MTL Kd albedo, computed and indexed normals, fan triangulation, errors.
#include <cmath>
#include <sstream>

#include <catch2/catch.hpp>
#include <glm/geometric.hpp>

#include "mesh/mesh.h"
#include "mesh_test_util.h"

using namespace prt::mesh;
using namespace prt::mesh::test;

namespace {

/// Outward CCW faces of the unit cube [0,1]^3, each with its own 4 vertices, and the face normals.
struct CubeFace {
  glm::vec3 corners[4];
  glm::vec3 normal;
};
const CubeFace kCube[6] = {
    {{{0, 0, 0}, {0, 0, 1}, {0, 1, 1}, {0, 1, 0}}, {-1, 0, 0}},
    {{{1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}}, {1, 0, 0}},
    {{{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}}, {0, -1, 0}},
    {{{0, 1, 0}, {0, 1, 1}, {1, 1, 1}, {1, 1, 0}}, {0, 1, 0}},
    {{{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}}, {0, 0, -1}},
    {{{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}, {0, 0, 1}},
};

double signed_volume(const Mesh& mesh) {
  double volume = 0.0;
  for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
    const glm::dvec3 a(mesh.positions[mesh.indices[t]]), b(mesh.positions[mesh.indices[t + 1]]),
        c(mesh.positions[mesh.indices[t + 2]]);
    volume += glm::dot(a, glm::cross(b, c)) / 6.0;
  }
  return volume;
}

}  // namespace

TEST_CASE("OBJ with MTL: vertex order and Kd albedo per material and file normals", "[mesh][obj]") {
  write_temp("mats.mtl", "newmtl red\nKd 0.8 0.1 0.2\n\nnewmtl blue\nKd 0.2 0.3 0.9\n");
  const std::string path = write_temp("materials.obj",
                                      "# test\nmtllib mats.mtl\n"
                                      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\n"
                                      "v 0 0 1\nv 1 0 1\nv 0 1 1\n"
                                      "v 5 5 5\n"  // used by no face
                                      "vn 0 0 1\n"
                                      "f 6//1 7//1 8//1\n"  // no material yet: Kd 0.8
                                      "usemtl red\nf 1//1 2//1 3//1\n"
                                      "usemtl blue\nf 1//1 3//1 4//1\nf 2//1 5//1 3//1\n");
  LoadReport report;
  const Mesh mesh = load_mesh(path, &report, true);
  REQUIRE(mesh.vertex_count() == 9);
  const glm::vec3 expected_positions[9] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0},
                                           {0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {5, 5, 5}};
  for (int i = 0; i < 9; ++i) CHECK(mesh.positions[i] == expected_positions[i]);
  CHECK(mesh.indices == std::vector<std::uint32_t>{5, 6, 7, 0, 1, 2, 0, 2, 3, 1, 4, 2});
  for (int i = 0; i < 8; ++i) CHECK(mesh.normals[i] == glm::vec3(0, 0, 1));
  CHECK(mesh.normals[8] == glm::vec3(0, 1, 0));  // no face: +Y
  CHECK_FALSE(report.normals_computed);
  REQUIRE(report.albedo_from_file);
  REQUIRE(mesh.albedo.size() == 9);
  // Vertices 1, 2, 3 (0-based 0, 1, 2) touch red and blue faces: the mean of the two Kd.
  for (int i : {0, 1, 2}) {
    CHECK(mesh.albedo[i].x == Approx(0.5).epsilon(1e-6));
    CHECK(mesh.albedo[i].y == Approx(0.2).epsilon(1e-6));
    CHECK(mesh.albedo[i].z == Approx(0.55).epsilon(1e-6));
  }
  for (int i : {3, 4}) CHECK(mesh.albedo[i] == glm::vec3(0.2f, 0.3f, 0.9f));
  for (int i : {5, 6, 7, 8}) CHECK(mesh.albedo[i] == glm::vec3(0.8f));
}

TEST_CASE("OBJ without normals: area-weighted normals of a tetrahedron corner", "[mesh][obj]") {
  // Corner tetrahedron O, X, Y, Z with outward CCW faces. The area-weighted normal at X sums the
  // cross products (0,-1,0) + (0,0,-1) + (1,1,1) = (1,0,0); at O it is (-1,-1,-1)/sqrt(3).
  const std::string path = write_temp("tetra.obj",
                                      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                                      "f 1 2 4\nf 1 4 3\nf 1 3 2\nf 2 3 4\n");
  LoadReport report;
  const Mesh mesh = load_mesh(path, &report, true);
  REQUIRE(mesh.triangle_count() == 4);
  CHECK(report.normals_computed);
  CHECK(report.computed_normal_count == 4);
  REQUIRE(report.notes.size() == 1);
  CHECK(report.notes[0] == "computed area-weighted normals for 4 of 4 vertices (the file has no normals)");
  CHECK(mesh.normals[1] == glm::vec3(1, 0, 0));
  CHECK(mesh.normals[2] == glm::vec3(0, 1, 0));
  CHECK(mesh.normals[3] == glm::vec3(0, 0, 1));
  const double k = -1.0 / std::sqrt(3.0);
  for (int c = 0; c < 3; ++c) CHECK(mesh.normals[0][c] == Approx(k).margin(1e-7));
  CHECK(mesh.albedo.empty());
  CHECK_FALSE(report.albedo_from_file);
  CHECK(signed_volume(mesh) == Approx(1.0 / 6.0).epsilon(1e-12));
}

TEST_CASE("OBJ quads and polygons are fan-triangulated and cube normals are the face normals", "[mesh][obj]") {
  std::ostringstream obj;
  for (const CubeFace& face : kCube)
    for (const glm::vec3& p : face.corners) obj << "v " << p.x << " " << p.y << " " << p.z << "\n";
  for (int f = 0; f < 6; ++f)
    obj << "f " << 4 * f + 1 << " " << 4 * f + 2 << " " << 4 * f + 3 << " " << 4 * f + 4 << "\n";
  const Mesh cube = load_mesh(write_temp("cube.obj", obj.str()), nullptr, true);
  REQUIRE(cube.vertex_count() == 24);
  REQUIRE(cube.triangle_count() == 12);
  for (std::uint32_t f = 0; f < 6; ++f) {
    const std::vector<std::uint32_t> expected = {4 * f, 4 * f + 1, 4 * f + 2, 4 * f, 4 * f + 2, 4 * f + 3};
    CHECK(std::vector<std::uint32_t>(cube.indices.begin() + 6 * f, cube.indices.begin() + 6 * f + 6) == expected);
    for (int k = 0; k < 4; ++k) {
      CHECK(cube.positions[4 * f + k] == kCube[f].corners[k]);
      CHECK(cube.normals[4 * f + k] == kCube[f].normal);
    }
  }
  CHECK(signed_volume(cube) == Approx(1.0).epsilon(1e-12));

  // A convex pentagon: (0,1,2), (0,2,3), (0,3,4).
  const Mesh pentagon = load_mesh(
      write_temp("pentagon.obj", "v 0 0 0\nv 2 0 0\nv 3 2 0\nv 1 3 0\nv -1 2 0\nf 1 2 3 4 5\n"), nullptr, true);
  CHECK(pentagon.indices == std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3, 0, 3, 4});
  for (const glm::vec3& n : pentagon.normals) CHECK(n == glm::vec3(0, 0, 1));
}

TEST_CASE("OBJ hard edges: a cube of 8 v and 6 vn is faceted, each face's vertices carry its normal exactly",
          "[mesh][obj][normals]") {
  // The 8 corners as "v" lines (corner x + 2y + 4z), the 6 face normals as "vn" lines, each face's
  // corners referencing its face normal: every corner is shared by 3 faces of 3 different normals.
  std::ostringstream obj;
  for (int c = 0; c < 8; ++c) obj << "v " << (c & 1) << " " << ((c >> 1) & 1) << " " << ((c >> 2) & 1) << "\n";
  for (const CubeFace& face : kCube) obj << "vn " << face.normal.x << " " << face.normal.y << " " << face.normal.z << "\n";
  for (int f = 0; f < 6; ++f) {
    obj << "f";
    for (const glm::vec3& p : kCube[f].corners) obj << " " << int(p.x + 2 * p.y + 4 * p.z) + 1 << "//" << f + 1;
    obj << "\n";
  }
  LoadReport report;
  const Mesh cube = load_mesh(write_temp("hard_cube.obj", obj.str()), &report, true);
  CHECK_FALSE(report.normals_computed);
  REQUIRE(cube.vertex_count() == 24);  // 8 "v"s keep their index, 16 copies follow
  REQUIRE(cube.triangle_count() == 12);
  for (int c = 0; c < 8; ++c) CHECK(cube.positions[c] == glm::vec3(c & 1, (c >> 1) & 1, (c >> 2) & 1));
  for (std::uint32_t f = 0; f < 6; ++f) {
    const int corner_of_triangle[6] = {0, 1, 2, 0, 2, 3};  // the fan of each quad
    for (int k = 0; k < 6; ++k) {
      const std::uint32_t vertex = cube.indices[6 * f + k];
      CHECK(cube.positions[vertex] == kCube[f].corners[corner_of_triangle[k]]);
      CHECK(cube.normals[vertex] == kCube[f].normal);
    }
  }
  // Copies are numbered in first-use order: the first mention of vertex 8 + k comes after that of 8 + k - 1.
  std::uint32_t next_copy = 8;
  for (std::uint32_t index : cube.indices)
    if (index >= 8) {
      CHECK(index <= next_copy);
      if (index == next_copy) ++next_copy;
    }
  CHECK(next_copy == 24);
  CHECK(signed_volume(cube) == Approx(1.0).epsilon(1e-12));
}

TEST_CASE("OBJ normals indexed apart from positions: a v with two normals is split, materials follow", "[mesh][obj][normals]") {
  // v2 is used with vn1 (faces 1 and 3) and vn2 (face 2): its first pair (v2, vn1) keeps index 1, (v2,
  // vn2) becomes vertex 5, after the 5 "v"s. vn3 has vn1's value: (v1, vn3) is v1's own pair, no split.
  write_temp("split.mtl", "newmtl red\nKd 0.8 0.1 0.2\n\nnewmtl blue\nKd 0.2 0.3 0.9\n");
  const std::string path = write_temp("indexed_normals.obj",
                                      "mtllib split.mtl\n"
                                      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 2 0 0\n"
                                      "vn 0 0 1\nvn 1 0 0\nvn -0 0 1\n"
                                      "usemtl blue\nf 1//1 2//1 3//1\nusemtl red\nf 2//2 4//2 3//1\n"
                                      "usemtl blue\nf 2//1 5//1 4//2\nf 1//3 5//1 3//1\n");
  LoadReport report;
  const Mesh mesh = load_mesh(path, &report, true);
  CHECK_FALSE(report.normals_computed);
  REQUIRE(mesh.vertex_count() == 6);
  CHECK(mesh.indices == std::vector<std::uint32_t>{0, 1, 2, 5, 3, 2, 1, 4, 3, 0, 4, 2});
  CHECK(mesh.positions[5] == glm::vec3(1, 0, 0));
  const glm::vec3 z(0, 0, 1), x(1, 0, 0);
  CHECK(mesh.normals == std::vector<glm::vec3>{z, z, z, x, z, x});
  const glm::vec3 red(0.8f, 0.1f, 0.2f), blue(0.2f, 0.3f, 0.9f);
  REQUIRE(mesh.albedo.size() == 6);
  CHECK(mesh.albedo[1] == blue);  // faces 1 and 3
  CHECK(mesh.albedo[5] == red);   // face 2 only
  CHECK(mesh.albedo[3] == glm::vec3((glm::dvec3(red) + glm::dvec3(blue)) / 2.0));
}

TEST_CASE("OBJ with a zero normal: that vertex's normal is computed, every other keeps the file's bit for bit",
          "[mesh][obj][normals]") {
  // A 3x3 grid of flat quads in z = 0 whose file normals lean (not the face normal, so computing them
  // all would show); vn 5 (the centre's) is zero and gets the area-weighted normal, +Z exactly.
  std::ostringstream obj;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) obj << "v " << i << " " << j << " 0\n";
  const char* leaning[4] = {"0.6 0 0.8", "0 0.6 0.8", "-0.28 0.96 0", "0.48 0.6 0.64"};
  for (int k = 0; k < 16; ++k) obj << "vn " << (k == 5 ? "0 0 0" : leaning[k % 4]) << "\n";
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      const int a = 4 * j + i + 1, b = a + 1, c = a + 5, d = a + 4;
      obj << "f " << a << "//" << a << " " << b << "//" << b << " " << c << "//" << c << " " << d << "//" << d << "\n";
    }
  LoadReport report;
  const Mesh mesh = load_mesh(write_temp("zero_normal.obj", obj.str()), &report, true);
  REQUIRE(mesh.vertex_count() == 16);
  CHECK(report.computed_normal_count == 1);
  CHECK(report.notes.back() ==
        "computed area-weighted normals for 1 of 16 vertices (1 referenced normals are zero or not finite)");
  for (int k = 0; k < 16; ++k) {
    if (k == 5) continue;
    float n[3];
    std::istringstream(leaning[k % 4]) >> n[0] >> n[1] >> n[2];
    CHECK(mesh.normals[k] == glm::vec3(n[0], n[1], n[2]));  // as parsed, not renormalised
  }
  CHECK(mesh.normals[5] == glm::vec3(0, 0, 1));
}

TEST_CASE("OBJ errors are one line naming the file and the problem", "[mesh][obj]") {
  const std::string out_of_range = write_temp("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
  CHECK(error_of([&] { load_mesh(out_of_range, nullptr, true); }) ==
        out_of_range + ": face 0 refers to vertex 9 (1-based), but the file has 3 vertices");
  const std::string negative = write_temp("negative.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -7\n");
  CHECK(error_of([&] { load_mesh(negative, nullptr, true); }) ==
        negative + ": face 0 refers to a vertex before the first");
  const std::string zero_index = write_temp("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n");
  CHECK_THAT(error_of([&] { load_mesh(zero_index, nullptr, true); }),
             Catch::StartsWith(zero_index + ": cannot read OBJ: "));
  const std::string no_faces = write_temp("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  CHECK(error_of([&] { load_mesh(no_faces, nullptr, true); }) == no_faces + ": no triangles (the file has no faces)");
  const std::string degenerate = write_temp("flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\nf 1 1 2\n");
  CHECK(error_of([&] { load_mesh(degenerate, nullptr, true); }) ==
        degenerate + ": no triangles left: all 2 are degenerate");
  const std::string infinite = write_temp("inf.obj", "v 0 0 0\nv 1e999 0 0\nv 0 1 0\nf 1 2 3\n");
  CHECK(error_of([&] { load_mesh(infinite, nullptr, true); }) ==
        infinite + ": line 2: vertex 2 (1-based) has a non-finite position \"v 1e999 0 0\"");
  const std::string nan = write_temp("nan.obj", "v 0 0 0\nv 1 0 0\n\n  v nan 0 0\nf 1 2 3\n");
  CHECK(error_of([&] { load_mesh(nan, nullptr, true); }) ==
        nan + ": line 4: vertex 3 (1-based) has a non-finite position \"v nan 0 0\"");
  const std::string word = write_temp("word.obj", "v 0 0 0\r\nv 1 zero 0\r\nv 0 1 0\r\nf 1 2 3\r\n");
  CHECK(error_of([&] { load_mesh(word, nullptr, true); }) ==
        word + ": line 2: vertex 2 (1-based) has a malformed position \"v 1 zero 0\"");
  const std::string short_line = write_temp("short.obj", "v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n");
  CHECK(error_of([&] { load_mesh(short_line, nullptr, true); }) ==
        short_line + ": line 2: vertex 2 (1-based) has a malformed position \"v 1 0\"");
  // Underflow is not an error: it rounds to zero (or a denormal) as strtod does.
  const Mesh tiny = load_mesh(write_temp("tiny.obj", "v 0 0 1e-60\nv +1 0 0\nv 0 1 0\nf 1 2 3\n"), nullptr, true);
  CHECK(tiny.positions[0] == glm::vec3(0, 0, 0));
  CHECK(tiny.positions[1] == glm::vec3(1, 0, 0));
  const std::string binary = write_temp("binary.obj", std::string("v 0 0 0\n\0\x01\x02garbage", 18));
  CHECK(error_of([&] { load_mesh(binary, nullptr, true); }) ==
        binary + ": not an OBJ text file (its content looks like binary data)");
  const std::string ply_inside = write_temp("ply_inside.obj", "ply\nformat ascii 1.0\n");
  CHECK(error_of([&] { load_mesh(ply_inside, nullptr, true); }) ==
        ply_inside + ": not an OBJ text file (its content looks like a PLY file)");
}

TEST_CASE("OBJ with a missing MTL loads without albedo and notes the warning", "[mesh][obj]") {
  LoadReport report;
  const Mesh mesh =
      load_mesh(write_temp("missing_mtl.obj", "mtllib nowhere.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n"),
                &report, true);
  CHECK(mesh.albedo.empty());
  REQUIRE(report.notes.size() == 2);
  CHECK_THAT(report.notes[0], Catch::StartsWith("OBJ reader: "));
}

TEST_CASE("OBJ PBR keys: each MTL material's Pr and Pm are its roughness and metallic factors", "[mesh][obj][materials]") {
  // Values chosen apart from every default (tinyobjloader's 0, prt's metallic 0 / roughness 1), and a
  // name with a trailing blank and a repeated definition (the first one counts, as for Kd).
  write_temp("pbr.mtl",
             "newmtl shiny \nKd 1 1 1\nPr 0.25\nPm 0.75\n"
             "newmtl plain\nKd 0.5 0.5 0.5\n"
             "newmtl half\r\nPm 1\r\nPr 0.0625\r\nmap_Pr rough.png\r\n"
             "newmtl shiny\nPr 0.5\nPm 0.5\n");
  const std::string path = write_temp("pbr.obj", "mtllib pbr.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\n"
                                                 "usemtl shiny\nf 1//1 2//1 3//1\nusemtl plain\nf 1//1 3//1 4//1\n"
                                                 "usemtl half\nf 2//1 3//1 4//1\n");
  const Mesh mesh = load_mesh(path, nullptr, true);
  REQUIRE(mesh.triangle_material.size() == 3);
  const Material& shiny = mesh.materials[mesh.triangle_material[0]];
  const Material& plain = mesh.materials[mesh.triangle_material[1]];
  const Material& half = mesh.materials[mesh.triangle_material[2]];
  CHECK(shiny.roughness_factor == 0.25f);
  CHECK(shiny.metallic_factor == 0.75f);
  CHECK_FALSE(shiny.metallic_roughness_textured);
  CHECK(plain.roughness_factor == 1.0f);  // MTL without Pr / Pm: a rough dielectric
  CHECK(plain.metallic_factor == 0.0f);
  CHECK(half.roughness_factor == 0.0625f);
  CHECK(half.metallic_factor == 1.0f);
  CHECK(half.metallic_roughness_textured);  // map_Pr is not read: noted where a glossy BRDF is made
}

TEST_CASE("OBJ PBR keys out of [0, 1] or not a number are one line naming the MTL file", "[mesh][obj][materials]") {
  const std::string obj = "mtllib bad.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl m\nf 1 2 3\n";
  const std::pair<const char*, const char*> cases[] = {
      {"newmtl m\nPr 1.5\n", "line 2: material m: Pr \"1.5\" is not one number in [0, 1]"},
      {"newmtl m\nKd 1 1 1\nPm -0.1\n", "line 3: material m: Pm \"-0.1\" is not one number in [0, 1]"},
      {"newmtl m\nPm nan\n", "line 2: material m: Pm \"nan\" is not one number in [0, 1]"},
      {"newmtl m\nPr 0.5 0.5\n", "line 2: material m: Pr \"0.5 0.5\" is not one number in [0, 1]"},
      {"newmtl m\nPr\n", "line 2: material m: Pr \"\" is not one number in [0, 1]"}};
  for (const auto& [mtl, problem] : cases) {
    const std::string mtl_path = write_temp("bad.mtl", mtl);
    const std::string path = write_temp("bad_pbr.obj", obj);
    CHECK(error_of([&] { load_mesh(path, nullptr, true); }) == mtl_path + ": " + problem);
  }
}
