// glTF loading (.gltf with an external or embedded buffer, .glb): scene selection, node transforms,
// instancing, strips, skipped line primitives, baseColorFactor x COLOR_0, normals by the inverse
// transpose, mirrored winding; errors; and garbled inputs.
#include <cmath>
#include <random>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "mesh/mesh.h"
#include "mesh_test_util.h"

using namespace prt::mesh;
using namespace prt::mesh::test;
using nlohmann::json;

namespace {

/// Builds a glTF buffer, its buffer views and accessors.
struct BufferBuilder {
  std::string bytes;
  json views = json::array();
  json accessors = json::array();

  int view(const std::string& data) {
    while (bytes.size() % 4) bytes.push_back('\0');
    views.push_back({{"buffer", 0}, {"byteOffset", bytes.size()}, {"byteLength", data.size()}});
    bytes += data;
    return int(views.size() - 1);
  }
  int accessor(int view_index, int component_type, std::size_t count, const char* type, bool normalized = false) {
    json a = {{"bufferView", view_index}, {"componentType", component_type}, {"count", count}, {"type", type}};
    if (normalized) a["normalized"] = true;
    accessors.push_back(a);
    return int(accessors.size() - 1);
  }
  int floats(const std::vector<float>& values, const char* type, int components) {
    std::string data;
    for (float v : values) put(data, v);
    return accessor(view(data), 5126, values.size() / std::size_t(components), type);
  }
  template <class T>
  int scalars(const std::vector<T>& values, int component_type, const char* type = "SCALAR", bool normalized = false,
              int components = 1) {
    std::string data;
    for (T v : values) put(data, v);
    return accessor(view(data), component_type, values.size() / std::size_t(components), type, normalized);
  }
};

/// The test scene: mesh 0 (a triangle with normals, material and float COLOR_0; a strip with ubyte
/// COLOR_0 and no normals; a line primitive) used by node 0 (TRS) and its child node 1, mesh 1 (a
/// slanted triangle with normals) used by node 2 (a mirroring scale) and by node 3, which is in
/// scene 0 only; "scene": 1.
json scene_document(BufferBuilder& b) {
  const int p0 = b.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
  const int n0 = b.floats({0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3", 3);
  const int c0 = b.floats({1, 0.5f, 0.5f, 0.5f, 1, 0.5f, 0.5f, 0.5f, 1}, "VEC3", 3);
  const int i0 = b.scalars<std::uint16_t>({0, 1, 2}, 5123);
  const int p1 = b.floats({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0}, "VEC3", 3);
  const int c1 = b.scalars<std::uint8_t>({255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 51, 102, 153, 255}, 5121,
                                         "VEC4", true, 4);
  const int p2 = b.floats({1, 0, 0, 0, 1, 0, 0, 0, 1}, "VEC3", 3);
  const float k = float(1.0 / std::sqrt(3.0));
  const int n2 = b.floats({k, k, k, k, k, k, k, k, k}, "VEC3", 3);
  const int i2 = b.scalars<std::uint32_t>({0, 1, 2}, 5125);
  json doc = {
      {"asset", {{"version", "2.0"}}},
      {"scene", 1},
      {"scenes", {{{"nodes", {3}}}, {{"nodes", {0, 2}}}}},
      {"nodes",
       {{{"translation", {10, 0, 0}}, {"rotation", {0, 0, 1, 0}}, {"scale", {2, 3, 4}}, {"mesh", 0}, {"children", {1}}},
        {{"translation", {0, 5, 0}}, {"mesh", 0}},
        {{"scale", {-1, 2, 1}}, {"mesh", 1}},
        {{"mesh", 1}}}},
      {"materials", {{{"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.25, 1.0, 1.0}}}}}}},
      {"meshes",
       {{{"primitives",
          {{{"attributes", {{"POSITION", p0}, {"NORMAL", n0}, {"COLOR_0", c0}}}, {"indices", i0}, {"material", 0}},
           {{"attributes", {{"POSITION", p1}, {"COLOR_0", c1}}}, {"mode", 5}},
           {{"attributes", {{"POSITION", p1}}}, {"mode", 1}}}}},
        {{"primitives", {{{"attributes", {{"POSITION", p2}, {"NORMAL", n2}}}, {"indices", i2}}}}}}},
  };
  doc["bufferViews"] = b.views;
  doc["accessors"] = b.accessors;
  return doc;
}

std::string make_glb(const json& doc_without_uri, std::string bin) {
  std::string text = doc_without_uri.dump();
  while (text.size() % 4) text.push_back(' ');
  while (bin.size() % 4) bin.push_back('\0');
  std::string glb;
  put(glb, std::uint32_t(0x46546C67));
  put(glb, std::uint32_t(2));
  put(glb, std::uint32_t(12 + 8 + text.size() + 8 + bin.size()));
  put(glb, std::uint32_t(text.size()));
  put(glb, std::uint32_t(0x4E4F534A));
  glb += text;
  put(glb, std::uint32_t(bin.size()));
  put(glb, std::uint32_t(0x004E4942));
  glb += bin;
  return glb;
}

void check_scene_mesh(const Mesh& mesh, const LoadReport& report) {
  // Order: node 0 (mesh 0: triangle, strip), node 1 (mesh 0 again), node 2 (mesh 1). Node 0 maps
  // p -> (10 - 2x, -3y, 4z); node 1 maps p -> (10 - 2x, -3(y + 5), 4z); node 2 maps p -> (-x, 2y, z).
  const std::vector<glm::vec3> expected = {{10, 0, 0},   {8, 0, 0},   {10, -3, 0},                // node 0, triangle
                                           {10, 0, 0},   {8, 0, 0},   {10, -3, 0},  {8, -3, 0},   // node 0, strip
                                           {10, -15, 0}, {8, -15, 0}, {10, -18, 0},               // node 1, triangle
                                           {10, -15, 0}, {8, -15, 0}, {10, -18, 0}, {8, -18, 0},  // node 1, strip
                                           {-1, 0, 0},   {0, 2, 0},   {0, 0, 1}};                 // node 2 (mirrored)
  REQUIRE(mesh.vertex_count() == expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    INFO("vertex " << i);
    CHECK(mesh.positions[i] == expected[i]);
  }
  // Strips: (v0, v1, v2), (v1, v3, v2). The mirrored triangle's winding is reversed.
  CHECK(mesh.indices ==
        std::vector<std::uint32_t>{0, 1, 2, 3, 4, 5, 4, 6, 5, 7, 8, 9, 10, 11, 12, 11, 13, 12, 14, 16, 15});
  for (std::size_t i = 0; i < 14; ++i) CHECK(mesh.normals[i] == glm::vec3(0, 0, 1));
  // (1,1,1)/sqrt(3) through the inverse transpose of diag(-1, 2, 1): (-2, 1, 2)/3.
  for (std::size_t i = 14; i < 17; ++i) {
    CHECK(mesh.normals[i].x == Approx(-2.0 / 3.0).epsilon(1e-6));
    CHECK(mesh.normals[i].y == Approx(1.0 / 3.0).epsilon(1e-6));
    CHECK(mesh.normals[i].z == Approx(2.0 / 3.0).epsilon(1e-6));
  }
  CHECK(report.normals_computed);
  CHECK(report.computed_normal_count == 8);
  CHECK(report.skipped_primitives == 2);
  REQUIRE(report.albedo_from_file);
  // baseColorFactor (0.5, 0.25, 1) times float COLOR_0; normalised ubyte COLOR_0 alone; no material: 1.
  const std::vector<glm::vec3> albedo = {{0.5f, 0.125f, 0.5f},
                                         {0.25f, 0.25f, 0.5f},
                                         {0.25f, 0.125f, 1.0f},
                                         {1, 0, 0},
                                         {0, 1, 0},
                                         {0, 0, 1},
                                         {float(51 / 255.0), float(102 / 255.0), float(153 / 255.0)}};
  for (std::size_t i = 0; i < 7; ++i) {
    CHECK(mesh.albedo[i] == albedo[i]);
    CHECK(mesh.albedo[i + 7] == albedo[i]);
  }
  for (std::size_t i = 14; i < 17; ++i) CHECK(mesh.albedo[i] == glm::vec3(1.0f));
  CHECK(report.notes ==
        std::vector<std::string>{"the file has 2 scenes; loaded only scene 1, the default (a scene can be chosen by "
                                 "index, or all of them)",
                                 "skipped 2 primitives in point or line modes or without POSITION",
                                 "computed area-weighted normals for 8 of 17 vertices (2 primitives have no normals)"});
}

}  // namespace

TEST_CASE("glTF with an external buffer: scene and transforms and instancing and albedo and normals", "[mesh][gltf]") {
  BufferBuilder b;
  json doc = scene_document(b);
  write_temp("scene.bin", b.bytes);
  doc["buffers"] = {{{"byteLength", b.bytes.size()}, {"uri", "scene.bin"}}};
  LoadReport report;
  const Mesh mesh = load_mesh(write_temp("scene.gltf", doc.dump(2)), &report, true);
  check_scene_mesh(mesh, report);

  SECTION("the same scene as .glb gives the same mesh") {
    json glb_doc = doc;
    glb_doc["buffers"] = {{{"byteLength", b.bytes.size()}}};
    LoadReport glb_report;
    const Mesh glb = load_mesh(write_temp("scene.glb", make_glb(glb_doc, b.bytes)), &glb_report, true);
    check_scene_mesh(glb, glb_report);
    CHECK(fingerprint(glb) == fingerprint(mesh));
  }
  SECTION("without \"scene\", scene 0 is used") {
    json scene0 = doc;
    scene0.erase("scene");
    const Mesh m = load_mesh(write_temp("scene0.gltf", scene0.dump()), nullptr, true);
    CHECK(m.positions == std::vector<glm::vec3>{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}});
    const float k = float(1.0 / std::sqrt(3.0));
    for (const glm::vec3& n : m.normals) CHECK(n == glm::vec3(k, k, k));
    CHECK(m.albedo.empty());
  }
  SECTION("without scenes, every root node in document order (embedded data URI)") {
    json roots = doc;
    roots.erase("scene");
    roots.erase("scenes");
    roots["buffers"] = {
        {{"byteLength", b.bytes.size()}, {"uri", "data:application/octet-stream;base64," + base64(b.bytes)}}};
    const Mesh m = load_mesh(write_temp("roots.gltf", roots.dump()), nullptr, true);
    REQUIRE(m.vertex_count() == 20);  // nodes 0, 1 (child of 0), 2, 3
    CHECK(m.positions[14] == glm::vec3(-1, 0, 0));
    CHECK(m.positions[17] == glm::vec3(1, 0, 0));
  }
}

TEST_CASE("glTF errors are one line naming the file and the problem", "[mesh][gltf]") {
  auto one_triangle = [](std::vector<float> positions, std::vector<std::uint32_t> indices) {
    BufferBuilder b;
    const int p = b.floats(positions, "VEC3", 3);
    const int i = b.scalars<std::uint32_t>(indices, 5125);
    json doc = {{"asset", {{"version", "2.0"}}},
                {"nodes", {{{"mesh", 0}}}},
                {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", p}}}, {"indices", i}}}}}}}};
    doc["bufferViews"] = b.views;
    doc["accessors"] = b.accessors;
    doc["buffers"] = {
        {{"byteLength", b.bytes.size()}, {"uri", "data:application/octet-stream;base64," + base64(b.bytes)}}};
    return doc;
  };
  const std::string good = write_temp("good.gltf", one_triangle({0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 1, 2}).dump());
  CHECK(load_mesh(good, nullptr, true).triangle_count() == 1);

  const std::string range = write_temp("range.gltf", one_triangle({0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 1, 5}).dump());
  CHECK(error_of([&] { load_mesh(range, nullptr, true); }) ==
        range + ": mesh 0 primitive 0: index 5 out of range (POSITION has 3 vertices)");
  const std::string nan = write_temp("nan.gltf", one_triangle({0, 0, 0, NAN, 0, 0, 0, 1, 0}, {0, 1, 2}).dump());
  CHECK(error_of([&] { load_mesh(nan, nullptr, true); }) ==
        nan + ": mesh 0 primitive 0: POSITION 1 is not finite (nan, 0, 0)");
  json long_count = one_triangle({0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 1, 2});
  long_count["accessors"][0]["count"] = 4;
  const std::string overrun = write_temp("overrun.gltf", long_count.dump());
  CHECK(error_of([&] { load_mesh(overrun, nullptr, true); }) ==
        overrun + ": mesh 0 primitive 0 POSITION: accessor runs past the end of its buffer view");
  json instanced = one_triangle({0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 1, 2});
  instanced["extensionsRequired"] = {"EXT_mesh_gpu_instancing"};
  instanced["extensionsUsed"] = {"EXT_mesh_gpu_instancing"};
  instanced["buffers"][0]["byteLength"] = 1u << 30;  // checked before any buffer is read
  const std::string unsupported = write_temp("instanced.gltf", instanced.dump());
  CHECK(error_of([&] { load_mesh(unsupported, nullptr, true); }) ==
        unsupported + ": requires glTF extension EXT_mesh_gpu_instancing, which prt does not support");
  json cyclic = one_triangle({0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 1, 2});
  cyclic["nodes"] = {{{"mesh", 0}, {"children", {1}}}, {{"children", {0}}}};
  cyclic["scenes"] = {{{"nodes", {0}}}};
  const std::string cycle = write_temp("cycle.gltf", cyclic.dump());
  CHECK(error_of([&] { load_mesh(cycle, nullptr, true); }) ==
        cycle + ": node 0 is reached twice (the node hierarchy must be a set of trees)");
  json dag = one_triangle({0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 1, 2});
  dag["nodes"] = json::array();
  for (int i = 0; i < 64; ++i) dag["nodes"].push_back({{"children", {i + 1, i + 1}}});  // 2^64 paths
  dag["nodes"].push_back({{"mesh", 0}});
  dag["scenes"] = {{{"nodes", {0}}}};
  const std::string shared = write_temp("dag.gltf", dag.dump());
  CHECK(error_of([&] { load_mesh(shared, nullptr, true); }) ==
        shared + ": node 64 is reached twice (the node hierarchy must be a set of trees)");
  json lines = one_triangle({0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 1, 2});
  lines["meshes"][0]["primitives"][0]["mode"] = 1;
  const std::string only_lines = write_temp("lines.gltf", lines.dump());
  CHECK(error_of([&] { load_mesh(only_lines, nullptr, true); }) ==
        only_lines + ": no triangles (the file has no faces)");
  const std::string broken = write_temp("broken.gltf", "{\"asset\": {\"version\": \"2.0\"}, \"nodes\": [");
  CHECK_THAT(error_of([&] { load_mesh(broken, nullptr, true); }), Catch::StartsWith(broken + ": cannot read glTF: "));
  const std::string not_glb = write_temp("text.glb", "{\"asset\": {}}");
  CHECK(error_of([&] { load_mesh(not_glb, nullptr, true); }) ==
        not_glb + ": not a binary glTF file (its content looks like JSON (.gltf))");
}

TEST_CASE("Garbled glTF and GLB files load or fail with prt::Error and never crash", "[mesh][gltf]") {
  BufferBuilder b;
  json doc = scene_document(b);
  json glb_doc = doc;
  glb_doc["buffers"] = {{{"byteLength", b.bytes.size()}}};
  const std::string glb = make_glb(glb_doc, b.bytes);
  doc["buffers"] = {
      {{"byteLength", b.bytes.size()}, {"uri", "data:application/octet-stream;base64," + base64(b.bytes)}}};
  const std::string text = doc.dump();
  std::mt19937 rng(777);
  int loaded = 0, refused = 0;
  for (const auto& [name, original] :
       {std::pair<std::string, std::string>{"garbled.glb", glb}, {"garbled.gltf", text}}) {
    for (std::size_t length = 0; length < original.size(); length += 1 + original.size() / 64) {
      try {
        load_mesh(write_temp(name, original.substr(0, length)), nullptr, true);
        ++loaded;
      } catch (const prt::Error&) {
        ++refused;
      }
    }
    for (int trial = 0; trial < 200; ++trial) {
      std::string bytes = original;
      const int flips = 1 + int(rng() % 4);
      for (int k = 0; k < flips; ++k) bytes[rng() % bytes.size()] = char(rng() % 256);
      try {
        load_mesh(write_temp(name, bytes), nullptr, true);
        ++loaded;
      } catch (const prt::Error&) {
        ++refused;
      }
    }
  }
  CHECK(refused > 0);
  INFO("loaded " << loaded << ", refused " << refused);
  SUCCEED("no crash and no exception other than prt::Error");
}

TEST_CASE("glTF with one zero normal: that vertex's normal is computed, the others kept bit for bit", "[mesh][gltf][normals]") {
  // Two triangles of the plane z = 0 whose NORMALs lean (not +Z, so computing them all would show);
  // vertex 2's is zero and gets the area-weighted normal, +Z exactly.
  BufferBuilder b;
  const int p = b.floats({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, "VEC3", 3);
  const int n = b.floats({0.6f, 0, 0.8f, 0, 0.6f, 0.8f, 0, 0, 0, 0.48f, 0.6f, 0.64f}, "VEC3", 3);
  const int i = b.scalars<std::uint32_t>({0, 1, 2, 0, 2, 3}, 5125);
  json doc = {{"asset", {{"version", "2.0"}}},
              {"nodes", {{{"mesh", 0}}}},
              {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", p}, {"NORMAL", n}}}, {"indices", i}}}}}}}};
  doc["bufferViews"] = b.views;
  doc["accessors"] = b.accessors;
  doc["buffers"] = {{{"byteLength", b.bytes.size()}, {"uri", "data:application/octet-stream;base64," + base64(b.bytes)}}};
  LoadReport report;
  const Mesh mesh = load_mesh(write_temp("zero_normal.gltf", doc.dump()), &report, true);
  CHECK(report.computed_normal_count == 1);
  CHECK(report.notes.back() ==
        "computed area-weighted normals for 1 of 4 vertices (1 of the file's normals are zero or not finite)");
  CHECK(mesh.normals[0] == glm::vec3(0.6f, 0.0f, 0.8f));
  CHECK(mesh.normals[1] == glm::vec3(0.0f, 0.6f, 0.8f));
  CHECK(mesh.normals[2] == glm::vec3(0, 0, 1));
  CHECK(mesh.normals[3] == glm::vec3(0.48f, 0.6f, 0.64f));
}
