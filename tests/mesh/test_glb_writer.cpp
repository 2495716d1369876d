// write_glb: the file is valid GLB (header, chunk padding, 4-byte aligned views, POSITION min/max),
// tinygltf reads every attribute back bit for bit, and load_mesh round-trips the geometry.
#include <cmath>
#include <limits>

#include <catch2/catch.hpp>
#include <tiny_gltf.h>

#include "mesh/mesh.h"
#include "mesh/writers.h"
#include "mesh_test_util.h"
#include "support/random_draws.h"

using namespace prt::mesh;
using namespace prt::mesh::test;

namespace {

bool skip_image(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
  return true;
}

std::uint32_t u32_at(const std::string& bytes, std::size_t offset) {
  std::uint32_t v = 0;
  for (int k = 0; k < 4; ++k) v |= std::uint32_t(std::uint8_t(bytes[offset + k])) << (8 * k);
  return v;
}

/// The accessor's data as raw 32-bit words (tightly packed, as write_glb writes them).
std::vector<std::uint32_t> words(const tinygltf::Model& model, int accessor_index, int components) {
  const tinygltf::Accessor& a = model.accessors.at(std::size_t(accessor_index));
  const tinygltf::BufferView& view = model.bufferViews.at(std::size_t(a.bufferView));
  const std::vector<unsigned char>& data = model.buffers.at(std::size_t(view.buffer)).data;
  std::vector<std::uint32_t> out(a.count * std::size_t(components));
  REQUIRE(view.byteOffset + a.byteOffset + out.size() * 4 <= data.size());
  std::memcpy(out.data(), data.data() + view.byteOffset + a.byteOffset, out.size() * 4);
  return out;
}

template <class V>
std::vector<std::uint32_t> words_of(const std::vector<V>& values) {
  std::vector<std::uint32_t> out(values.size() * sizeof(V) / 4);
  std::memcpy(out.data(), values.data(), out.size() * 4);
  return out;
}

}  // namespace

TEST_CASE("write_glb writes a valid GLB that reads back bit for bit", "[mesh][gltf][writer]") {
  // Geometry: a unit cube from the OBJ loader (normals computed, unit length).
  std::string obj;
  const float corners[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  for (const auto& c : corners)
    obj += "v " + std::to_string(c[0]) + " " + std::to_string(c[1]) + " " + std::to_string(c[2]) + "\n";
  obj += "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
  Mesh mesh = load_mesh(write_temp("glb_cube.obj", obj), nullptr, true);
  mesh.positions[6] = {1.25f, 1.0f, 1.5f};  // make min/max differ per axis
  const std::size_t n = mesh.vertex_count();

  // Radiance above 1 too: COLOR_0 holds L / (1 + L) (glTF requires [0, 1]), _PRT_RADIANCE holds L.
  std::vector<glm::vec3> colours(n), displayed(n);
  for (std::size_t i = 0; i < n; ++i) colours[i] = glm::vec3(4.0f * float(i) / n, 0.5f, 1.0f - float(i) / n);
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) displayed[i][c] = colours[i][c] / (1.0f + colours[i][c]);

  const std::string path = temp_path("baked.glb");
  write_glb(path, mesh, colours);
  const std::string bytes = read_bytes(path);

  // GLB header and chunks.
  REQUIRE(bytes.size() >= 28);
  CHECK(bytes.substr(0, 4) == "glTF");
  CHECK(u32_at(bytes, 4) == 2);
  CHECK(u32_at(bytes, 8) == bytes.size());
  const std::uint32_t json_length = u32_at(bytes, 12);
  CHECK(u32_at(bytes, 16) == 0x4E4F534Au);
  CHECK(json_length % 4 == 0);
  const std::size_t bin_header = 20 + json_length;
  CHECK(u32_at(bytes, bin_header + 4) == 0x004E4942u);
  CHECK(u32_at(bytes, bin_header) % 4 == 0);
  CHECK(bin_header + 8 + u32_at(bytes, bin_header) == bytes.size());

  tinygltf::TinyGLTF gltf;
  gltf.SetImageLoader(skip_image, nullptr);
  tinygltf::Model model;
  std::string err, warn;
  REQUIRE(gltf.LoadBinaryFromFile(&model, &err, &warn, path));
  CHECK(err.empty());
  CHECK(model.asset.version == "2.0");
  REQUIRE(model.meshes.size() == 1);
  REQUIRE(model.meshes[0].primitives.size() == 1);
  const tinygltf::Primitive& prim = model.meshes[0].primitives[0];
  CHECK(prim.mode == TINYGLTF_MODE_TRIANGLES);
  CHECK(prim.attributes.size() == 4);

  for (const tinygltf::BufferView& view : model.bufferViews) {
    CHECK(view.byteOffset % 4 == 0);
    CHECK(view.byteStride == 0);
  }
  auto check_float_attribute = [&](const std::string& name, int type, const std::vector<std::uint32_t>& expected) {
    INFO(name);
    REQUIRE(prim.attributes.count(name) == 1);
    const tinygltf::Accessor& a = model.accessors.at(std::size_t(prim.attributes.at(name)));
    CHECK(a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT);
    CHECK(a.type == type);
    CHECK(a.count == n);
    CHECK(model.bufferViews.at(std::size_t(a.bufferView)).target == TINYGLTF_TARGET_ARRAY_BUFFER);
    CHECK(words(model, prim.attributes.at(name), type == TINYGLTF_TYPE_VEC3 ? 3 : 4) == expected);
  };
  check_float_attribute("POSITION", TINYGLTF_TYPE_VEC3, words_of(mesh.positions));
  check_float_attribute("NORMAL", TINYGLTF_TYPE_VEC3, words_of(mesh.normals));
  check_float_attribute("COLOR_0", TINYGLTF_TYPE_VEC3, words_of(displayed));
  check_float_attribute("_PRT_RADIANCE", TINYGLTF_TYPE_VEC3, words_of(colours));

  // POSITION min/max: exactly the extreme float values, as the spec requires.
  const tinygltf::Accessor& position = model.accessors.at(std::size_t(prim.attributes.at("POSITION")));
  const Bounds box = bounds(mesh);
  CHECK(position.minValues == std::vector<double>{box.lo.x, box.lo.y, box.lo.z});
  CHECK(position.maxValues == std::vector<double>{box.hi.x, box.hi.y, box.hi.z});

  const tinygltf::Accessor& indices = model.accessors.at(std::size_t(prim.indices));
  CHECK(indices.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
  CHECK(indices.type == TINYGLTF_TYPE_SCALAR);
  CHECK(model.bufferViews.at(std::size_t(indices.bufferView)).target == TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  CHECK(words(model, prim.indices, 1) == mesh.indices);

  // prt's own loader: the same geometry, bit for bit; COLOR_0 becomes the albedo.
  LoadReport report;
  const Mesh back = load_mesh(path, &report, true);
  CHECK(words_of(back.positions) == words_of(mesh.positions));
  CHECK(words_of(back.normals) == words_of(mesh.normals));
  CHECK(back.indices == mesh.indices);
  CHECK(back.albedo == displayed);
  CHECK(fingerprint(back) == fingerprint(mesh));
  CHECK_FALSE(report.normals_computed);
}

TEST_CASE("write_glb refuses an empty mesh with a one-line error", "[mesh][gltf][writer]") {
  Mesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  mesh.indices = {0, 1, 2};
  const std::string path = temp_path("bad.glb");
  CHECK(error_of([&] { write_glb(path, Mesh{}); }) == path + ": cannot write glTF: the mesh is empty");
  CHECK_FALSE(std::filesystem::exists(path));
  // No colour: a valid file with POSITION and NORMAL only.
  write_glb(path, mesh);
  const Mesh back = load_mesh(path, nullptr, true);
  CHECK(back.positions == mesh.positions);
  CHECK(back.albedo.empty());
}
