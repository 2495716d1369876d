// write_glb_textured (the lightmap glTF's mesh half): vertices split by lightmap UV exactly where a
// vertex has several UVs, the per-corner positions and UVs read back bit for bit by tinygltf and by
// prt's own loader, the images stored byte for byte, the extension used and not required.
#include <cstring>
#include <set>

#include <catch2/catch.hpp>
#include <tiny_gltf.h>

#include "mesh/mesh.h"
#include "mesh/writers.h"
#include "mesh_test_util.h"

using namespace prt::mesh;
using namespace prt::mesh::test;

namespace {

bool keep_image(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) { return true; }

// A cube whose six faces are separate charts: 8 positions, 24 distinct (vertex, UV) corners.
std::string cube_obj() {
  std::string obj;
  const float corners[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  for (const auto& c : corners) obj += "v " + std::to_string(c[0]) + " " + std::to_string(c[1]) + " " + std::to_string(c[2]) + "\n";
  for (int f = 0; f < 6; ++f) {
    const float u0 = 0.02f + 0.33f * float(f % 3), v0 = 0.02f + 0.5f * float(f / 3);
    for (const auto& [du, dv] : {std::pair{0.0f, 0.0f}, std::pair{0.3f, 0.0f}, std::pair{0.3f, 0.45f}, std::pair{0.0f, 0.45f}})
      obj += "vt " + std::to_string(u0 + du) + " " + std::to_string(v0 + dv) + "\n";
  }
  const int faces[6][4] = {{1, 4, 3, 2}, {5, 6, 7, 8}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 4, 8, 7}, {4, 1, 5, 8}};
  for (int f = 0; f < 6; ++f) {
    obj += "f";
    for (int k = 0; k < 4; ++k) obj += " " + std::to_string(faces[f][k]) + "/" + std::to_string(4 * f + k + 1);
    obj += "\n";
  }
  return obj;
}

}  // namespace

TEST_CASE("write_glb_textured splits vertices by lightmap UV and round-trips corners, images and extension", "[mesh][gltf][writer]") {
  const Mesh mesh = load_mesh(write_temp("textured_cube.obj", cube_obj()), nullptr, true);
  REQUIRE(mesh.vertex_count() == 8);
  REQUIRE(mesh.lightmap_uv.size() == 36);
  std::set<std::pair<std::uint32_t, std::pair<float, float>>> distinct;
  for (std::size_t c = 0; c < mesh.indices.size(); ++c)
    distinct.insert({mesh.indices[c], {mesh.lightmap_uv[c].x, mesh.lightmap_uv[c].y}});
  REQUIRE(distinct.size() == 24);

  const std::vector<GlbImage> images = {{std::string("\xABKTX 20\xBB\r\n\x1A\n-first", 18), "image/ktx2"},
                                        {std::string("second image, 27 bytes long"), "image/ktx2"}};
  const std::string path = temp_path("textured.glb");
  write_glb_textured(path, mesh, images, "PRT_test_extension", R"({"transfer": 0, "bounceOnly": 1, "bands": 3})");

  tinygltf::TinyGLTF gltf;
  gltf.SetImageLoader(keep_image, nullptr);
  tinygltf::Model model;
  std::string err, warn;
  REQUIRE(gltf.LoadBinaryFromFile(&model, &err, &warn, path));
  CHECK(err.empty());
  CHECK(model.extensionsUsed == std::vector<std::string>{"PRT_test_extension"});
  CHECK(model.extensionsRequired.empty());
  const tinygltf::Primitive& prim = model.meshes.at(0).primitives.at(0);
  REQUIRE(prim.extensions.count("PRT_test_extension") == 1);
  CHECK(prim.extensions.at("PRT_test_extension").Get("bounceOnly").GetNumberAsInt() == 1);
  CHECK(model.accessors.at(std::size_t(prim.attributes.at("POSITION"))).count == 24);
  CHECK(model.accessors.at(std::size_t(prim.attributes.at("TEXCOORD_0"))).count == 24);
  REQUIRE(model.images.size() == 2);
  for (std::size_t i = 0; i < 2; ++i) {
    const tinygltf::BufferView& view = model.bufferViews.at(std::size_t(model.images[i].bufferView));
    const auto& data = model.buffers.at(0).data;
    CHECK(model.images[i].mimeType == "image/ktx2");
    CHECK(std::string(data.begin() + long(view.byteOffset), data.begin() + long(view.byteOffset + view.byteLength)) == images[i].bytes);
  }

  // prt's own loader: the same corners (position and UV, bit for bit) in the same order.
  const Mesh back = load_mesh(path, nullptr, true);
  REQUIRE(back.vertex_count() == 24);
  REQUIRE(back.indices.size() == mesh.indices.size());
  REQUIRE(back.lightmap_uv.size() == mesh.lightmap_uv.size());
  for (std::size_t c = 0; c < mesh.indices.size(); ++c) {
    CHECK(same_bits(back.positions[back.indices[c]], mesh.positions[mesh.indices[c]]));
    CHECK(float_bits(back.lightmap_uv[c].x) == float_bits(mesh.lightmap_uv[c].x));
    CHECK(float_bits(back.lightmap_uv[c].y) == float_bits(mesh.lightmap_uv[c].y));
  }
  CHECK(fingerprint(back) != fingerprint(mesh));  // split vertices: a new mesh, hence a new transfer file
  CHECK(uv_fingerprint(back) == uv_fingerprint(mesh));

  CHECK_THROWS_WITH(write_glb_textured(temp_path("bad.glb"), mesh, images, "PRT_x", "[1, 2]"), Catch::Contains("not a JSON object"));
  Mesh no_uv = mesh;
  no_uv.lightmap_uv.clear();
  CHECK_THROWS_WITH(write_glb_textured(temp_path("bad.glb"), no_uv, images, "PRT_x", "{}"), Catch::Contains("no lightmap UVs"));
}
