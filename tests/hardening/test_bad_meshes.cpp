// Hostile mesh files (issue 10's list): each gives one prt::Error naming the file, never a crash, a
// read past the end, a wrapped index, a hang or a silent NaN.
#include <sys/stat.h>

#include <catch2/catch.hpp>
#include <string>

#include "core/atomic_file.h"
#include "core/error.h"
#include "hardening/bad_input_files.h"
#include "mesh/mesh.h"

namespace prt::test {
namespace {

using Catch::Matchers::Contains;

std::string put(const std::string& name, const std::string& bytes) {
  return write_in("hardening_meshes", name, bytes);
}

TEST_CASE("a GLB whose BIN chunk claims 8 bytes more than the file holds is refused", "[hardening][gltf]") {
  std::string glb = make_glb(triangle_gltf_json(R"({"byteLength":36})"), triangle_positions());
  // The control: the intact file loads.
  REQUIRE(mesh::load_mesh(put("good.glb", glb), nullptr, true).triangle_count() == 1);
  // BIN chunk length field = 8 bytes before the end of the header part; add 8.
  const std::size_t bin_header = glb.size() - 36 - 8;
  std::string forged = glb;
  const std::uint32_t claimed = 36 + 8;
  for (int k = 0; k < 4; ++k) forged[bin_header + k] = static_cast<char>((claimed >> (8 * k)) & 0xff);
  const std::string path = put("bin_overrun.glb", forged);
  REQUIRE_THROWS_WITH(mesh::load_mesh(path, nullptr, true), Contains(path) && Contains("more than the file holds"));
}

TEST_CASE("GLB version 1 and a short total length are refused", "[hardening][gltf]") {
  const std::string glb = make_glb(triangle_gltf_json(R"({"byteLength":36})"), triangle_positions());
  std::string v1 = glb;
  v1[4] = 1;
  REQUIRE_THROWS_WITH(mesh::load_mesh(put("v1.glb", v1), nullptr, true), Contains("GLB version 1"));
  std::string short_length = glb;
  short_length[8] = static_cast<char>(short_length[8] - 4);  // total length 4 bytes short of the file
  REQUIRE_THROWS_WITH(mesh::load_mesh(put("short.glb", short_length), nullptr, true),
                      Contains("total length of " + std::to_string(glb.size() - 4)));
}

TEST_CASE("a glTF with extras nested 20000 deep is refused before parsing", "[hardening][gltf]") {
  const std::string deep = R"("extras":)" + std::string(20000, '[') + std::string(20000, ']');
  const std::string path = put("deep.gltf", triangle_gltf_json(R"({"byteLength":36,"uri":"tri.bin"})", deep));
  put("tri.bin", triangle_positions());
  REQUIRE_THROWS_WITH(mesh::load_mesh(path, nullptr, true), Contains(path) && Contains("nested deeper than 64"));
  // The control: 60 levels are fine.
  const std::string ok = R"("extras":)" + std::string(60, '[') + std::string(60, ']');
  REQUIRE(mesh::load_mesh(put("shallow.gltf", triangle_gltf_json(R"({"byteLength":36,"uri":"tri.bin"})", ok)),
                          nullptr, true)
              .triangle_count() == 1);
}

TEST_CASE("a GLB buffer of byteLength 0 is a prt::Error, not vector::at's text", "[hardening][gltf]") {
  const std::string glb = make_glb(triangle_gltf_json(R"({"byteLength":0})"), triangle_positions());
  const std::string path = put("zero_buffer.glb", glb);
  REQUIRE_THROWS_AS(mesh::load_mesh(path, nullptr, true), prt::Error);
  REQUIRE_THROWS_WITH(mesh::load_mesh(path, nullptr, true), Contains(path) && !Contains("range_check"));
}

TEST_CASE("a glTF buffer uri that names a folder or a FIFO is refused", "[hardening][gltf]") {
  ::mkdir((temp_folder("hardening_meshes") + "/a_folder.bin").c_str(), 0755);
  const std::string folder = put("uri_folder.gltf", triangle_gltf_json(R"({"byteLength":36,"uri":"a_folder.bin"})"));
  REQUIRE_THROWS_WITH(mesh::load_mesh(folder, nullptr, true), Contains(folder) && Contains("folder"));
  ::mkfifo((temp_folder("hardening_meshes") + "/a_fifo.bin").c_str(), 0644);
  const std::string fifo = put("uri_fifo.gltf", triangle_gltf_json(R"({"byteLength":36,"uri":"a_fifo.bin"})"));
  REQUIRE_THROWS_WITH(mesh::load_mesh(fifo, nullptr, true), Contains("not a regular file"));
}

TEST_CASE("a FIFO or a device as the mesh is refused instead of blocking or reading forever", "[hardening][io]") {
  const std::string fifo = temp_folder("hardening_meshes") + "/pipe.obj";
  ::mkfifo(fifo.c_str(), 0644);
  REQUIRE_THROWS_WITH(mesh::load_mesh(fifo, nullptr, true), Contains(fifo) && Contains("not a regular file"));
  REQUIRE_THROWS_WITH(read_file("/dev/zero"), Contains("/dev/zero") && Contains("not a regular file"));
}

TEST_CASE("an OBJ face index of 4294967297 does not wrap to vertex 1", "[hardening][obj]") {
  const std::string path = put("wrap.obj", triangle_obj("0 0 0", "1 0 0", "0 1 0", "f 4294967297 2 3"));
  REQUIRE_THROWS_WITH(mesh::load_mesh(path, nullptr, true), Contains(path) && Contains("4294967297"));
  // The control: 1 2 3 loads.
  REQUIRE(mesh::load_mesh(put("nowrap.obj", triangle_obj("0 0 0", "1 0 0", "0 1 0")), nullptr, true)
              .triangle_count() == 1);
}

TEST_CASE("OBJ texture coordinates and normals are parsed as strictly as positions", "[hardening][obj]") {
  // tinyobjloader reads "nan" and "abc" as 0: the lightmap would bake at (0, 0.7) without a word.
  const std::string face = "f 1/1/1 2/2/1 3/3/1";
  auto obj = [&](const std::string& vt2, const std::string& vn) {
    return triangle_obj("0 0 0", "1 0 0", "0 1 0", "vt 0 0\n" + vt2 + "\nvt 0 1\n" + vn + "\n" + face);
  };
  const std::string nan = put("vt_nan.obj", obj("vt nan 0.7", "vn 0 0 1"));
  REQUIRE_THROWS_WITH(mesh::load_mesh(nan, nullptr, true),
                      nan + ": line 5: texture coordinate 2 (1-based) has a non-finite value \"vt nan 0.7\"");
  const std::string word = put("vt_word.obj", obj("vt abc 0.7", "vn 0 0 1"));
  REQUIRE_THROWS_WITH(mesh::load_mesh(word, nullptr, true),
                      word + ": line 5: texture coordinate 2 (1-based) has a malformed value \"vt abc 0.7\"");
  const std::string normal = put("vn_nan.obj", obj("vt 1 0", "vn 0 nan 1"));
  REQUIRE_THROWS_WITH(mesh::load_mesh(normal, nullptr, true), Contains(normal) && Contains("line 7: normal 1 (1-based)"));
  const std::string overflow = put("vt_1e39.obj", obj("vt 1e39 0.7", "vn 0 0 1"));
  REQUIRE_THROWS_WITH(mesh::load_mesh(overflow, nullptr, true), Contains("non-finite value"));
  // The control: the same file with numbers everywhere loads, with its UVs (v flipped: prt's v is down).
  const mesh::Mesh ok = mesh::load_mesh(put("vt_ok.obj", obj("vt 1 0.25", "vn 0 0 1")), nullptr, true);
  REQUIRE(ok.triangle_count() == 1);
  REQUIRE(ok.lightmap_uv.size() == 3);
  REQUIRE(ok.lightmap_uv[1].x == 1.0f);
  REQUIRE(ok.lightmap_uv[1].y == 0.75f);
}

TEST_CASE("vertices beyond +-1e12 (3.4e38 reached Embree) are refused", "[hardening][range]") {
  const std::string path = put("huge.obj", triangle_obj("0 0 0", "3.4e38 0 0", "0 1 0"));
  REQUIRE_THROWS_WITH(mesh::load_mesh(path, nullptr, true), Contains(path) && Contains("outside +-1e12"));
  // A mesh scaled by 1e19 (NaN in glossy shading) is refused too; 1e11 is accepted.
  REQUIRE_THROWS_WITH(mesh::load_mesh(put("e19.obj", triangle_obj("0 0 0", "1e19 0 0", "0 1e19 0")), nullptr, true),
                      Contains("outside +-1e12"));
  REQUIRE(mesh::load_mesh(put("e11.obj", triangle_obj("0 0 0", "1e11 0 0", "0 1e11 0")), nullptr, true)
              .triangle_count() == 1);
}

TEST_CASE("a mesh scaled by 1e-20 is refused - 1e-8 is accepted", "[hardening][range]") {
  REQUIRE_THROWS_WITH(
      mesh::load_mesh(put("tiny.obj", triangle_obj("0 0 0", "1e-20 0 0", "0 1e-20 0")), nullptr, true),
      Contains("below 1e-9"));
  const mesh::Mesh small = mesh::load_mesh(put("small.obj", triangle_obj("0 0 0", "1e-8 0 0", "0 1e-8 0")), nullptr, true);
  REQUIRE(small.triangle_count() == 1);
  REQUIRE(small.normals[0].z == Approx(1.0f));  // area-weighted normal of a counter-clockwise triangle
}

TEST_CASE("material emission that overflows float (Ke 1e39) names the file", "[hardening][range]") {
  put("hot.mtl", "newmtl hot\nKd 0.5 0.5 0.5\nKe 1e39 1 1\n");
  const std::string path = put("hot.obj", "mtllib hot.mtl\nusemtl hot\n" + triangle_obj("0 0 0", "1 0 0", "0 1 0"));
  REQUIRE_THROWS_WITH(mesh::load_mesh(path, nullptr, true), Contains(path) && Contains("emission"));
  // glTF emissiveFactor x emissiveStrength of 1e300 as well.
  const std::string gltf = triangle_gltf_json(
      R"({"byteLength":36,"uri":"tri.bin"})",
      R"("materials":[{"emissiveFactor":[1,1,1],"extensions":{"KHR_materials_emissive_strength":{"emissiveStrength":1e300}}}])");
  std::string with_material = gltf;
  with_material.replace(with_material.find(R"({"attributes":{"POSITION":0}})"), 29,
                        R"({"attributes":{"POSITION":0},"material":0})");
  put("tri.bin", triangle_positions());
  REQUIRE_THROWS_WITH(mesh::load_mesh(put("hot.gltf", with_material), nullptr, true), Contains("emission"));
}

}  // namespace
}  // namespace prt::test
