// Emission: glTF emissiveFactor x KHR_materials_emissive_strength per primitive, OBJ/MTL Ke averaged per
// vertex over its materials like Kd; empty when nothing emits; negative values become 0; vertex order 1:1.
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "mesh/mesh.h"
#include "mesh_test_util.h"

using namespace prt::mesh;
using namespace prt::mesh::test;
using nlohmann::json;

namespace {

// Three triangles, one primitive each: material 0 (emissive, strength 4), material 1 (not emissive),
// no material.
std::string emissive_gltf(bool any_emission) {
  std::string bin;
  for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) put(bin, v);
  json material0 = {{"emissiveFactor", {1.0, 0.5, 0.25}}};
  if (any_emission) material0["extensions"] = {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4.0}}}};
  else material0["emissiveFactor"] = {0.0, 0.0, 0.0};
  json primitives = json::array();
  primitives.push_back({{"attributes", {{"POSITION", 0}}}, {"material", 0}});
  primitives.push_back({{"attributes", {{"POSITION", 0}}}, {"material", 1}});
  primitives.push_back({{"attributes", {{"POSITION", 0}}}});
  json doc;
  doc["asset"] = {{"version", "2.0"}};
  doc["extensionsUsed"] = json::array({"KHR_materials_emissive_strength"});
  doc["scenes"] = json::array({{{"nodes", json::array({0})}}});
  doc["nodes"] = json::array({{{"mesh", 0}}});
  json material1;
  material1["pbrMetallicRoughness"] = {{"baseColorFactor", {0.5, 0.5, 0.5, 1.0}}};
  doc["materials"] = json::array({material0, material1});
  json mesh0;
  mesh0["primitives"] = primitives;
  doc["meshes"] = json::array({mesh0});
  json buffer;
  buffer["byteLength"] = bin.size();
  buffer["uri"] = "data:application/octet-stream;base64," + base64(bin);
  doc["buffers"] = json::array({buffer});
  json view;
  view["buffer"] = 0;
  view["byteOffset"] = 0;
  view["byteLength"] = bin.size();
  doc["bufferViews"] = json::array({view});
  json accessor;
  accessor["bufferView"] = 0;
  accessor["componentType"] = 5126;
  accessor["count"] = 3;
  accessor["type"] = "VEC3";
  doc["accessors"] = json::array({accessor});
  return doc.dump();
}

}  // namespace

TEST_CASE("glTF emission is emissiveFactor times emissiveStrength per primitive", "[mesh][emission]") {
  LoadReport report;
  const Mesh mesh = load_mesh(write_temp("emissive.gltf", emissive_gltf(true)), &report, true);
  REQUIRE(mesh.vertex_count() == 9);
  REQUIRE(mesh.emission.size() == 9);
  CHECK(report.emission_from_file);
  for (int i = 0; i < 3; ++i) {
    CHECK(mesh.emission[i] == glm::vec3(4.0f, 2.0f, 1.0f));
    CHECK(mesh.emission[3 + i] == glm::vec3(0.0f));
    CHECK(mesh.emission[6 + i] == glm::vec3(0.0f));
  }
  const Mesh dark = load_mesh(write_temp("dark.gltf", emissive_gltf(false)), &report, true);
  CHECK(dark.emission.empty());
  CHECK_FALSE(report.emission_from_file);
}

TEST_CASE("OBJ emission is the per-vertex mean of the faces' materials' Ke", "[mesh][emission]") {
  write_temp("glow.mtl", "newmtl glow\nKd 0.5 0.5 0.5\nKe 2 1 0.5\nnewmtl plain\nKd 0.8 0.8 0.8\nnewmtl bad\nKe -1 3 0\n");
  const std::string obj = "mtllib glow.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 2 2 0\nv 3 2 0\nv 2 3 0\n"
                          "usemtl glow\nf 1 2 3\nusemtl plain\nf 2 4 3\nusemtl bad\nf 5 6 7\n";
  LoadReport report;
  const Mesh mesh = load_mesh(write_temp("glow.obj", obj), &report, true);
  REQUIRE(mesh.emission.size() == 7);
  CHECK(report.emission_from_file);
  CHECK(mesh.emission[0] == glm::vec3(2.0f, 1.0f, 0.5f));   // glow only
  CHECK(mesh.emission[1] == glm::vec3(1.0f, 0.5f, 0.25f));  // glow and plain
  CHECK(mesh.emission[3] == glm::vec3(0.0f));               // plain only
  CHECK(mesh.emission[4] == glm::vec3(0.0f, 3.0f, 0.0f));   // negative Ke -> 0
  const Mesh plain = load_mesh(write_temp("plain.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"), nullptr, true);
  CHECK(plain.emission.empty());
}
