// Compressed glTF (KHR_draco_mesh_compression, EXT_meshopt_compression) against an independent
// decoder (gltf-transform's, tests/data/gltf, scripts/make_compressed_gltf.sh) and closed forms (the
// meshopt filters, evaluated in double); glTF scene selection (mesh::LoadOptions::scene).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <meshoptimizer.h>
#include <nlohmann/json.hpp>

#include "mesh/gltf_compressed.h"
#include "mesh/mesh.h"
#include "mesh_test_util.h"

using namespace prt::mesh;
using namespace prt::mesh::test;
using nlohmann::json;

namespace {

const std::string kData = std::string(PRT_SOURCE_DIR) + "/tests/data/gltf/";

/// A data-uri buffer of a triangle's float positions, at x offset `x`.
json triangle_buffer(float x) {
  std::string data;
  for (float v : {x, 0.0f, 0.0f, x + 1.0f, 0.0f, 0.0f, x, 1.0f, 0.0f}) put(data, v);
  return {{"byteLength", data.size()}, {"uri", "data:application/octet-stream;base64," + base64(data)}};
}

/// Two meshes (triangles at x = 0 and x = 10) in nodes 0 and 1; scene 0 holds node 0, scene 1 holds
/// nodes 1 and 0 (a node may be in several scenes); "scene": 1.
json two_scene_document() {
  json doc = {{"asset", {{"version", "2.0"}}}, {"scene", 1}};
  for (int m = 0; m < 2; ++m) {
    doc["buffers"].push_back(triangle_buffer(m == 0 ? 0.0f : 10.0f));
    doc["bufferViews"].push_back({{"buffer", m}, {"byteLength", 36}});
    doc["accessors"].push_back({{"bufferView", m}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}});
    doc["meshes"].push_back({{"primitives", {{{"attributes", {{"POSITION", m}}}}}}});
    doc["nodes"].push_back({{"mesh", m}});
  }
  doc["scenes"] = {{{"nodes", {0}}}, {{"nodes", {1, 0}}}};
  return doc;
}

std::vector<float> xs(const Mesh& mesh) {
  std::vector<float> out;
  for (const glm::vec3& p : mesh.positions) out.push_back(p.x);
  return out;
}

}  // namespace

TEST_CASE("Draco and meshopt glTF load as gltf-transform decodes them, bit for bit", "[mesh][gltf]") {
  for (const char* codec : {"draco", "meshopt"}) {
    INFO(codec);
    const Mesh compressed = load_mesh(kData + "box_textured_" + codec + ".glb", nullptr, true);
    const Mesh plain = load_mesh(kData + "box_textured_" + codec + "_decoded.glb", nullptr, true);
    CHECK(compressed.vertex_count() == 24);
    CHECK(compressed.triangle_count() == 12);
    CHECK(compressed.positions == plain.positions);
    CHECK(compressed.normals == plain.normals);
    CHECK(compressed.indices == plain.indices);
    CHECK(compressed.lightmap_uv == plain.lightmap_uv);
    CHECK(compressed.albedo == plain.albedo);
  }
}

TEST_CASE("meshopt EXPONENTIAL filter and index sequence decode to their closed form", "[mesh][gltf]") {
  // Each float is stored as a 32-bit word: exponent e (signed 8 bits) on top, mantissa m (signed 24
  // bits) below, the value m * 2^e (EXT_meshopt_compression, "Filters").
  const int pairs[9][2] = {{0, 0}, {0, 0}, {0, 0}, {3, -1}, {0, 0}, {0, 0}, {0, 0}, {5, 2}, {-7, -3}};
  std::string words;
  for (const auto& p : pairs) put(words, (std::uint32_t(std::uint8_t(std::int8_t(p[1]))) << 24) | (std::uint32_t(p[0]) & 0xFFFFFFu));
  std::vector<unsigned char> vertices(meshopt_encodeVertexBufferBound(3, 12));
  vertices.resize(meshopt_encodeVertexBuffer(vertices.data(), vertices.size(), words.data(), 3, 12));
  const unsigned int order[3] = {2, 0, 1};
  std::vector<unsigned char> indices(meshopt_encodeIndexSequenceBound(3, 3));
  indices.resize(meshopt_encodeIndexSequence(indices.data(), indices.size(), order, 3));
  const std::string compressed = std::string(vertices.begin(), vertices.end()) + std::string(indices.begin(), indices.end());
  auto meshopt = [](std::size_t offset, std::size_t length, int stride, const char* mode) {
    return json{{"EXT_meshopt_compression", {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", length},
                                              {"byteStride", stride}, {"count", 3}, {"mode", mode}}}};
  };
  json doc = {{"asset", {{"version", "2.0"}}},
              {"extensionsUsed", {"EXT_meshopt_compression"}},
              {"extensionsRequired", {"EXT_meshopt_compression"}},
              {"buffers", {{{"byteLength", compressed.size()}, {"uri", "data:application/octet-stream;base64," + base64(compressed)}},
                           {{"byteLength", 42}, {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}}}},
              {"bufferViews", {{{"buffer", 1}, {"byteLength", 36}, {"byteStride", 12},
                                {"extensions", meshopt(0, vertices.size(), 12, "ATTRIBUTES")}},
                               {{"buffer", 1}, {"byteOffset", 36}, {"byteLength", 6},
                                {"extensions", meshopt(vertices.size(), indices.size(), 2, "INDICES")}}}},
              {"accessors", {{{"bufferView", 0}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}},
                             {{"bufferView", 1}, {"componentType", 5123}, {"count", 3}, {"type", "SCALAR"}}}},
              {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}}}}}}},
              {"nodes", {{{"mesh", 0}}}},
              {"scenes", {{{"nodes", {0}}}}}};
  doc["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["filter"] = "EXPONENTIAL";
  const Mesh mesh = load_mesh(write_temp("exponential.gltf", doc.dump()), nullptr, true);
  CHECK(mesh.positions == std::vector<glm::vec3>{{0.0f, 0.0f, 0.0f}, {1.5f, 0.0f, 0.0f}, {0.0f, 20.0f, -0.875f}});
  CHECK(mesh.indices == std::vector<std::uint32_t>{2, 0, 1});

  doc["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["filter"] = "QUATERNION";  // needs byteStride 8
  const std::string bad = write_temp("bad_filter.gltf", doc.dump());
  CHECK(error_of([&] { load_mesh(bad, nullptr, true); }) ==
        bad + ": buffer view 0 (EXT_meshopt_compression): filter \"QUATERNION\" is invalid for mode ATTRIBUTES and byteStride 12");
}

TEST_CASE("glTF scenes: the default one with a note, one by index, or all in order", "[mesh][gltf]") {
  const std::string path = write_temp("two_scenes.gltf", two_scene_document().dump());
  LoadReport report;
  CHECK(xs(load_mesh(path, LoadOptions{kDefaultScene, true}, &report)) == std::vector<float>{10, 11, 10, 0, 1, 0});
  CHECK(report.notes.at(0) ==
        "the file has 2 scenes; loaded only scene 1, the default (a scene can be chosen by index, or all of them)");
  CHECK(xs(load_mesh(path, LoadOptions{0, true}, &report)) == std::vector<float>{0, 1, 0});
  CHECK(report.notes == std::vector<std::string>{"computed area-weighted normals for 3 of 3 vertices (1 primitives have no normals)"});
  CHECK(xs(load_mesh(path, LoadOptions{kAllScenes, true})) == std::vector<float>{0, 1, 0, 10, 11, 10, 0, 1, 0});
  CHECK(error_of([&] { load_mesh(path, LoadOptions{2, true}); }) == path + ": scene 2 does not exist (the file has 2 scenes)");

  const std::string obj = write_temp("one_scene.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  CHECK(xs(load_mesh(obj, LoadOptions{kAllScenes, true})) == std::vector<float>{0, 1, 0});
  CHECK(xs(load_mesh(obj, LoadOptions{0, true})) == std::vector<float>{0, 1, 0});
  CHECK(error_of([&] { load_mesh(obj, LoadOptions{1, true}); }) == obj + ": scene 1 does not exist (the file has 1 scene)");
}

namespace {

/// The spec's octahedral decoding in double: round(c * one / |(x, y, z)|) per component, with the
/// lower hemisphere folded back; `tie` set when a component lies within 1e-4 of a rounding tie
/// (where float and double may round apart).
std::array<int, 3> octahedral_truth(int a, int b, int stored_one, bool* tie) {
  double x = a, y = b;
  const double z = stored_one - std::abs(x) - std::abs(y);
  const double t = std::min(z, 0.0);
  x += x >= 0 ? t : -t;
  y += y >= 0 ? t : -t;
  const double scale = stored_one / std::sqrt(x * x + y * y + z * z);
  std::array<int, 3> out{};
  const double c[3] = {x * scale, y * scale, z * scale};
  for (int k = 0; k < 3; ++k) {
    // float32 carries the products to within a few ulps: 1e-6 relative
    if (std::abs(std::abs(c[k] - std::floor(c[k])) - 0.5) < 1e-6 * std::max(1.0, std::abs(c[k]))) *tie = true;
    out[std::size_t(k)] = int(std::lround(c[k]));
  }
  return out;
}

}  // namespace

TEST_CASE("meshopt OCTAHEDRAL filter: every 8-bit code and a sweep of 16-bit codes against the closed form", "[mesh][gltf]") {
  // Counts per width: [0] 8-bit, [1] 16-bit.
  std::size_t checked[2] = {}, ties[2] = {}, wrong[2] = {};
  auto check = [&](int a, int b, int one, auto zero) {
    using T = decltype(zero);
    const std::size_t w = sizeof(T) - 1;
    T v[4] = {T(a), T(b), T(one), T(77)};  // w is kept
    prt::mesh::detail::apply_meshopt_filter("OCTAHEDRAL", reinterpret_cast<unsigned char*>(v), 1, sizeof(v));
    bool tie = false;
    const std::array<int, 3> truth = octahedral_truth(a, b, one, &tie);
    ++checked[w];
    if (tie) ++ties[w];
    else if (int(v[0]) != truth[0] || int(v[1]) != truth[1] || int(v[2]) != truth[2] || v[3] != T(77)) ++wrong[w];
  };
  for (int a = -127; a <= 127; ++a)
    for (int b = -127; b <= 127; ++b) check(a, b, 127, std::int8_t(0));
  for (int a = -32767; a <= 32767; a += 97)
    for (int b = -32767; b <= 32767; b += 89) check(a, b, 32767, std::int16_t(0));
  CHECK(checked[0] == 255 * 255);
  CHECK(ties[0] < checked[0] / 1000);  // 8-bit: few products come within 1.3e-4 of a tie
  CHECK(ties[1] < checked[1] / 10);    // 16-bit: the window is 0.03 at 32767
  CHECK(wrong[0] == 0);
  CHECK(wrong[1] == 0);
}

TEST_CASE("meshopt QUATERNION filter against the closed form", "[mesh][gltf]") {
  // Largest component index 1 (w goes to slot 1), scale bits 0x7FFC | 3 = 32767: x = 16384 / 32767 / sqrt(2).
  std::int16_t v[4] = {16384, -8000, 0, std::int16_t(0x7FFC | 1)};
  prt::mesh::detail::apply_meshopt_filter("QUATERNION", reinterpret_cast<unsigned char*>(v), 1, 8);
  const double x = 16384.0 / 32767.0 / std::sqrt(2.0), y = -8000.0 / 32767.0 / std::sqrt(2.0);
  const double w = std::sqrt(1.0 - x * x - y * y);
  CHECK(v[1] == std::lround(w * 32767.0));
  CHECK(v[2] == std::lround(x * 32767.0));
  CHECK(v[3] == std::lround(y * 32767.0));
  CHECK(v[0] == 0);
}
