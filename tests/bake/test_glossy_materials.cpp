// `--brdf mesh` (issue 33): each glTF material's metallic-roughness factors as its own BRDF in one
// glossy bake. Truth: a bake of the whole mesh with that one BRDF (per vertex, bit for bit), and the
// glossy reference path tracer with that BRDF (the tolerance of test_glossy_reference.cpp).
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <glm/common.hpp>
#include <glm/vector_relational.hpp>

#include "bake/bake.h"
#include "bake/mesh_brdfs.h"
#include "brdf/brdf.h"
#include "brdf/projection.h"
#include "image/compare.h"
#include "light/environment.h"
#include "light/light_file.h"
#include "light/projection.h"
#include "mesh/mesh.h"
#include "mesh/mesh_test_util.h"
#include "mesh/writers.h"
#include "reference/glossy_estimator.h"
#include "shade/glossy.h"
#include "shade/scene_shading.h"
#include "glossy_sky.h"
#include "support/run_prt.h"
#include "support/shapes.h"
#include "transfer/transfer_file.h"

using namespace prt;
using nlohmann::json;

namespace {

// The two materials, as glTF states them and as `--brdf` spells them (prt's gltf lobe).
const char* kSpecFloor = "gltf:basecolor=0.8/0.5/0.3,metallic=0,roughness=0.3";
const char* kSpecWall = "gltf:basecolor=0.6/0.6/0.7,metallic=0.6,roughness=0.8";

// An n x n grid: corner + i/(n-1) a + j/(n-1) b, normal `normal`, into `bin` (positions, normals,
// indices) and its primitive's accessors into `doc`.
json grid_primitive(std::string& bin, json& doc, glm::vec3 corner, glm::vec3 a, glm::vec3 b, glm::vec3 normal, int n, int material) {
  auto add_view = [&](std::size_t offset, std::size_t count, int type, const char* shape) {
    doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bin.size() - offset}});
    doc["accessors"].push_back({{"bufferView", doc["bufferViews"].size() - 1}, {"componentType", type}, {"count", count}, {"type", shape}});
    return doc["accessors"].size() - 1;
  };
  const std::size_t p0 = bin.size();
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const glm::vec3 p = corner + a * (float(i) / float(n - 1)) + b * (float(j) / float(n - 1));
      for (float x : {p.x, p.y, p.z}) mesh::test::put(bin, x);
    }
  const auto positions = add_view(p0, std::size_t(n * n), 5126, "VEC3");
  const glm::vec3 lo = glm::min(corner, corner + a + b), hi = glm::max(corner, corner + a + b);
  doc["accessors"][positions]["min"] = {lo.x, lo.y, lo.z};
  doc["accessors"][positions]["max"] = {hi.x, hi.y, hi.z};
  const std::size_t n0 = bin.size();
  for (int k = 0; k < n * n; ++k)
    for (float x : {normal.x, normal.y, normal.z}) mesh::test::put(bin, x);
  const auto normals = add_view(n0, std::size_t(n * n), 5126, "VEC3");
  const std::size_t i0 = bin.size();
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i)
      for (int c : {0, 1, n + 1, 0, n + 1, n}) mesh::test::put(bin, std::uint32_t(j * n + i + c));
  const auto indices = add_view(i0, std::size_t(6 * (n - 1) * (n - 1)), 5125, "SCALAR");
  return {{"attributes", {{"POSITION", positions}, {"NORMAL", normals}}}, {"indices", indices}, {"material", material}};
}

// A floor (y = 0, normal +Y, material 0) and a wall standing on it (z = -0.3, normal +Z, material 1),
// one primitive each, 6 x 6 vertices each: the wall shadows part of the floor.
std::string write_two_material_gltf(const std::string& dir) {
  json doc;
  doc["asset"] = {{"version", "2.0"}};
  doc["bufferViews"] = json::array();
  doc["accessors"] = json::array();
  std::string bin;
  json primitives = json::array();
  const int n = 6;
  primitives.push_back(grid_primitive(bin, doc, {-1, 0, -1}, {0, 0, 2}, {2, 0, 0}, {0, 1, 0}, n, 0));
  primitives.push_back(grid_primitive(bin, doc, {-1, 0.02f, -0.3f}, {2, 0, 0}, {0, 1.5f, 0}, {0, 0, 1}, n, 1));
  doc["materials"] = json::array(
      {{{"pbrMetallicRoughness", {{"baseColorFactor", {0.8, 0.5, 0.3, 1.0}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.3}}}},
       {{"pbrMetallicRoughness", {{"baseColorFactor", {0.6, 0.6, 0.7, 1.0}}, {"metallicFactor", 0.6}, {"roughnessFactor", 0.8}}}}});
  doc["meshes"] = json::array({{{"primitives", primitives}}});
  doc["nodes"] = json::array({{{"mesh", 0}}});
  doc["scenes"] = json::array({{{"nodes", json::array({0})}}});
  doc["buffers"] = json::array({{{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + mesh::test::base64(bin)}}});
  const std::string path = dir + "/two_materials.gltf";
  std::ofstream(path) << doc.dump();
  return path;
}

std::string write_dim_light(const std::string& dir) {
  sh::RgbCoefficients l(3);
  l.values[0] = glm::dvec3(0.5, 0.45, 0.4);
  l.values[2] = glm::dvec3(0.3, 0.25, 0.2);
  l.values[3] = glm::dvec3(-0.15, -0.1, -0.05);
  const std::string path = dir + "/light.json";
  light::write_light_file(path, l, {});
  return path;
}

bool contains(const std::string& haystack, const std::string& needle) { return haystack.find(needle) != std::string::npos; }

std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

}  // namespace

// Lobe by lobe, parameters and weights within `tolerance`.
bool same_brdf(const brdf::Brdf& a, const brdf::Brdf& b, double tolerance) {
  if (a.lobes.size() != b.lobes.size()) return false;
  for (std::size_t i = 0; i < a.lobes.size(); ++i) {
    const brdf::Lobe &x = a.lobes[i], &y = b.lobes[i];
    if (x.type != y.type || x.fresnel_mix != y.fresnel_mix || std::abs(x.roughness - y.roughness) > tolerance ||
        std::abs(x.exponent - y.exponent) > tolerance || glm::any(glm::greaterThan(glm::abs(x.weight - y.weight), glm::dvec3(tolerance))))
      return false;
  }
  return true;
}

TEST_CASE("prt bake --brdf mesh: a two-material glTF shades each vertex as the bake with its material's BRDF alone", "[glossy][cli][materials]") {
  // glossy-shadowed: the transfer is geometry only, so a vertex's shading depends on its own BRDF alone
  // (interreflection, where the other material's BRDF colours the bounce, is the next test's).
  const std::string dir = test::fresh_temp_dir("glossy_materials");
  const std::string gltf = write_two_material_gltf(dir);
  const std::string light = write_dim_light(dir);
  const std::string common = "bake " + gltf + " --transfer glossy-shadowed --bands 3 --samples 64 -q";
  // No --brdf: the default for a file with materials is --brdf mesh.
  const test::RunResult multi = test::run_prt(common + " -o " + dir + "/multi.prt");
  INFO(multi.output);
  REQUIRE(multi.exit_code == 0);
  const json parameters = json::parse(transfer::read_transfer(dir + "/multi.prt").header.parameters_json);
  REQUIRE(parameters["brdfs"].size() == 2);
  CHECK(parameters["brdf_runs"] == json::parse("[[0, 36], [1, 36]]"));
  CHECK(!parameters.contains("brdf"));
  // The recorded BRDFs are the glTF factors (as floats: within float rounding of the spec's decimals).
  const std::string floor_spec = parameters["brdfs"][0], wall_spec = parameters["brdfs"][1];
  CHECK(same_brdf(brdf::parse_brdf(floor_spec), brdf::parse_brdf(kSpecFloor), 1e-7));
  CHECK(same_brdf(brdf::parse_brdf(wall_spec), brdf::parse_brdf(kSpecWall), 1e-7));
  REQUIRE(test::run_prt(common + " --brdf " + floor_spec + " -o " + dir + "/floor.prt").exit_code == 0);
  REQUIRE(test::run_prt(common + " --brdf " + wall_spec + " -o " + dir + "/wall.prt").exit_code == 0);
  std::vector<mesh::Mesh> shaded;
  for (const char* name : {"multi", "floor", "wall"}) {
    const test::RunResult run = test::run_prt("shade " + gltf + " " + dir + "/" + name + ".prt --light " + light +
                                              " --eye 0.5,2,3 --window none -o " + dir + "/" + name + ".ply");
    INFO(run.output);
    REQUIRE(run.exit_code == 0);
    shaded.push_back(mesh::load_mesh(dir + "/" + name + ".ply", nullptr, true));
  }
  REQUIRE(shaded[0].albedo.size() == 72);
  double largest = 0.0;
  int differ = 0;
  for (std::size_t v = 0; v < 72; ++v) {
    const glm::vec3 own = shaded[v < 36 ? 1 : 2].albedo[v], other = shaded[v < 36 ? 2 : 1].albedo[v];
    CHECK(shaded[0].albedo[v] == own);
    differ += other != own;
    largest = std::max(largest, double(glm::max(own.r, glm::max(own.g, own.b))));
  }
  CHECK(differ > 60);      // the two BRDFs shade differently, so the choice per vertex shows
  CHECK(largest > 0.05);
  CHECK(largest < 1.0);    // the PLY loader clamps colours to [0, 1]
  // Any thread count gives the same bytes.
  REQUIRE(test::run_prt(common + " --brdf mesh --threads 1 -o " + dir + "/one.prt").exit_code == 0);
  CHECK(read_bytes(dir + "/one.prt") == read_bytes(dir + "/multi.prt"));
  // prt compress keeps each vertex's BRDF: a lossless CPCA (one cluster, as many directions as the 72
  // vertices need) shades as the .prt, vertex by vertex, in prt shade (prt render: test_render_cpca.cpp).
  const test::RunResult compressed = test::run_prt("compress " + dir + "/multi.prt --clusters 1 --pca 71 --light " + light + " -o " + dir + "/c.cprt");
  INFO(compressed.output);
  REQUIRE(compressed.exit_code == 0);
  REQUIRE(test::run_prt("shade " + gltf + " " + dir + "/c.cprt --light " + light + " --eye 0.5,2,3 --window none -o " + dir +
                        "/c.ply").exit_code == 0);
  const mesh::Mesh from_cprt = mesh::load_mesh(dir + "/c.ply", nullptr, true);
  REQUIRE(from_cprt.albedo.size() == 72);
  for (std::size_t v = 0; v < 72; ++v)
    for (int c = 0; c < 3; ++c) CHECK(from_cprt.albedo[v][c] == Approx(shaded[0].albedo[v][c]).margin(2e-4 * largest));
  // --brdf mesh on a mesh without materials is refused in one line.
  const mesh::Mesh plain = test::bowl(3, 6);
  mesh::write_ply(dir + "/plain.ply", plain.positions, {}, plain.indices);
  for (const char* brdf : {"", " --brdf mesh"})
    CHECK(test::fails_in_one_line(test::run_prt("bake " + dir + "/plain.ply --transfer glossy-shadowed" + brdf + " -o " + dir + "/p.prt"),
                                  "plain.ply: has no materials"));
  CHECK(!std::filesystem::exists(dir + "/p.prt"));
}

TEST_CASE("mesh_brdfs: a vertex takes its first triangle's BRDF, equal materials share an entry, notes", "[glossy][materials]") {
  // Three triangles in a strip (vertices 0-1-2, 1-3-2, 3-4-2), materials 1, 0, 2; materials 0 and 2 are
  // equal, material 1 has roughness 0 and a metallic-roughness texture.
  mesh::Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {2, 1, 0}};
  m.normals.assign(5, glm::vec3(0, 0, 1));
  m.indices = {0, 1, 2, 1, 3, 2, 3, 4, 2};
  m.materials.resize(3);
  m.materials[0].roughness_factor = 0.5f;
  m.materials[1].roughness_factor = 0.0f;
  m.materials[1].metallic_roughness_textured = true;
  m.materials[2].roughness_factor = 0.5f;
  m.triangle_material = {1, 0, 2};
  std::vector<std::string> notes;
  const brdf::VertexBrdfs b = bake::mesh_brdfs(m, &notes);
  REQUIRE(b.table.size() == 2);  // material 1 first (triangle 0), then 0 and 2 together
  CHECK(b.table[0].lobes.back().roughness == Approx(0.01));
  CHECK(b.table[1].lobes.back().roughness == Approx(0.5));
  CHECK(b.vertex == std::vector<std::uint32_t>{0, 0, 0, 1, 1});
  REQUIRE(notes.size() == 3);
  CHECK(contains(notes[0], "2 vertices join triangles of different materials"));  // vertices 1 and 2
  CHECK(contains(notes[1], "1 materials have roughness below 0.01"));
  CHECK(contains(notes[2], "1 materials have base colour or metallic-roughness textures"));
  // One distinct BRDF: no per-vertex indices (the file's single-BRDF form).
  m.triangle_material = {0, 0, 2};
  notes.clear();
  const brdf::VertexBrdfs one = bake::mesh_brdfs(m, &notes);
  CHECK(one.table.size() == 1);
  CHECK(one.vertex.empty());
}

namespace {

// Two bowls (test::bowl) 3 apart, material 0 on the first, 1 on the second. Each bowl lies below its
// rim's plane and every ray that leaves one crosses that plane upward, so neither sees the other: a
// vertex's interreflected transfer involves its own bowl's BRDF only.
mesh::Mesh two_bowls(int rings, int segments) {
  mesh::Mesh m = test::bowl(rings, segments);
  const std::size_t n = m.positions.size(), triangles = m.indices.size() / 3;
  for (std::size_t v = 0; v < n; ++v) {
    m.positions.push_back(m.positions[v] + glm::vec3(3.0f, 0.0f, 0.0f));
    m.normals.push_back(m.normals[v]);
  }
  for (std::size_t i = 0; i < 3 * triangles; ++i) m.indices.push_back(m.indices[i] + static_cast<std::uint32_t>(n));
  m.materials.resize(2);
  m.materials[0].base_color_factor = glm::vec3(0.8f, 0.6f, 0.4f);
  m.materials[0].metallic_factor = 0.5f;
  m.materials[0].roughness_factor = 0.4f;
  m.materials[1].base_color_factor = glm::vec3(0.5f, 0.6f, 0.7f);
  m.materials[1].metallic_factor = 0.0f;
  m.materials[1].roughness_factor = 0.7f;
  m.triangle_material.assign(2 * triangles, 0u);
  std::fill(m.triangle_material.begin() + static_cast<std::ptrdiff_t>(triangles), m.triangle_material.end(), 1u);
  return m;
}

}  // namespace

TEST_CASE("prt bake --brdf mesh interreflected: each vertex as the bake with its own BRDF, and the reference agrees",
          "[glossy][materials][reference][slow]") {
  const int bands = 5;
  const mesh::Mesh mesh = two_bowls(10, 20);
  const std::size_t half = mesh.positions.size() / 2;
  bake::BakeOptions o;
  o.kind = transfer::Kind::glossy_interreflected;
  o.bands = bands;
  o.samples = 8192;
  o.bounces = 1;
  o.brdf_from_mesh = true;
  bake::BakeReport report;
  const transfer::TransferData multi = bake::bake(mesh, o, &report);
  const brdf::VertexBrdfs brdfs = shade::baked_brdfs(multi.header, "multi");
  REQUIRE(brdfs.table.size() == 2);
  CHECK(report.notes.empty());
  const light::Environment env = test::directional_sky();
  const sh::RgbCoefficients lighting = light::project(env, bands);
  const reference::EnvironmentSampler limited(reference::band_limited_environment(env, bands));
  const glm::vec3 eye(1.5f, 3.0f, 2.5f);
  const std::vector<glm::vec3> got = shade::shade_glossy_vertex_brdfs(mesh, multi, brdfs, {lighting, {}, {}, 0.0, false}, eye, "multi");
  for (std::uint32_t k = 0; k < 2; ++k) {
    // The same mesh baked with material k's BRDF alone (its recorded spec, as --brdf would give it).
    o.brdf_from_mesh = false;
    o.brdf = brdfs.table[k];
    const transfer::TransferData single = bake::bake(mesh, o);
    const std::vector<glm::vec3> own =
        shade::shade_glossy_eye(single, brdf::project(o.brdf, bands), lighting, mesh.positions, mesh.normals, eye);
    // The reference path tracer with that BRDF, on the same mesh (the other bowl is out of sight).
    reference::GlossyReferenceOptions r;
    r.estimator.brdf = o.brdf;
    r.estimator.brdf_bands = bands;
    r.estimator.bounces = 1;
    r.samples = 8192;
    r.eye = glm::dvec3(eye);
    const std::vector<glm::vec3> truth = reference::glossy_vertex_radiance(mesh, limited, r);
    std::vector<glm::vec3> mine, theirs;
    for (std::size_t v = k * half; v < (k + 1) * half; ++v) {
      CHECK(brdfs.of(v) == k);
      CHECK(got[v] == own[v]);
      mine.push_back(got[v]);
      theirs.push_back(truth[v]);
    }
    const double error = image::compare_values(&mine[0].x, &theirs[0].x, 3 * mine.size()).rel_rms;
    INFO("material " << k << ": rel_rms against the reference " << error);
    CHECK(error <= 0.02);
  }
}
