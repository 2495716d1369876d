// The texel variant of .prt (round trip, layout, corruption), lightmap UVs in the loaders (OBJ vt,
// glTF TEXCOORD_1 over TEXCOORD_0, PLY u, v), `prt bake --lightmap` determinism, `prt info`, and bad
// input: one-line errors and no partial file.
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/error.h"
#include "lightmap/lightmap_scenes.h"
#include "mesh/mesh.h"
#include "support/run_prt.h"
#include "transfer/transfer_file.h"

namespace prt {

namespace {

std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_bytes(const std::string& path, const std::string& bytes) { std::ofstream(path, std::ios::binary) << bytes; }

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

transfer::TransferData small_texel_file(bool bounce) {
  transfer::TransferData d;
  transfer::Header& h = d.header;
  h.kind = bounce ? transfer::Kind::interreflected : transfer::Kind::shadowed;
  h.bands = 2;
  h.channels = 3;
  h.vertex_count = 7;
  h.triangle_count = 3;
  h.mesh_fingerprint = 0x1234;
  h.texel_width = 5;
  h.texel_height = 3;
  h.uv_set = 1;
  h.uv_fingerprint = 0xabcdef;
  h.bounce_only_section = bounce;
  h.parameters_json = "{}";
  d.coverage = {0, 1, 2, 1, 1, 2, 2, 0, 1, 1, 0, 0, 1, 2, 1};
  d.values.assign(15 * 12, 0.0f);
  for (std::size_t t = 0; t < 15; ++t)
    for (std::size_t k = 0; k < 12 && d.coverage[t]; ++k) d.values[t * 12 + k] = float(t) + 0.25f * float(k);
  if (bounce)
    for (float v : d.values) d.bounce_only.push_back(0.5f * v);
  return d;
}

}  // namespace

TEST_CASE("texel transfer files: round trip, version, layout and corruption", "[lightmap][transfer]") {
  const std::string dir = test::fresh_temp_dir("lightmap_files");
  for (bool bounce : {false, true}) {
    const transfer::TransferData d = small_texel_file(bounce);
    const std::string path = dir + "/t.prt";
    transfer::write_transfer(path, d);
    const transfer::TransferData r = transfer::read_transfer(path);
    CHECK(r.header.texel_width == 5);
    CHECK(r.header.texel_height == 3);
    CHECK(r.header.uv_set == 1);
    CHECK(r.header.uv_fingerprint == 0xabcdef);
    CHECK(r.header.vertex_count == 7);
    CHECK(r.coverage == d.coverage);
    CHECK(r.values == d.values);
    CHECK(r.bounce_only == d.bounce_only);
    const std::string bytes = read_bytes(path);
    std::uint32_t version = 0;
    std::memcpy(&version, bytes.data() + 8, 4);
    CHECK(version == (bounce ? 4u : 3u));
    // Layout of docs/formats.md: header (76 + P "{}" = 78 -> 80), texel block (24), checksum (8), then
    // the mask (15 bytes padded to 16) and the values.
    CHECK(bytes.size() == 80 + 24 + 8 + 16 + (bounce ? 2 : 1) * 15 * 12 * 4);
    CHECK(bytes.substr(112, 15) == std::string(d.coverage.begin(), d.coverage.end()));
    CHECK(transfer::describe(r.header).find("lightmap: 5x3 texels (UV set 1") != std::string::npos);
    CHECK(error_of([&] { transfer::check_uv_match(path, r.header, 0xabcdee); }).find("different lightmap UVs") != std::string::npos);
    CHECK(error_of([&] { transfer::check_uv_match(path, r.header, 0xabcdef); }).empty());
  }
  // A per-vertex file is as before (version 1, no texel block).
  transfer::TransferData v = small_texel_file(false);
  v.header.texel_width = v.header.texel_height = 0;
  v.coverage.clear();
  v.values.resize(7 * 12);
  transfer::write_transfer(dir + "/v.prt", v);
  CHECK(read_bytes(dir + "/v.prt").size() == 80 + 8 + 7 * 12 * 4);
  // A coverage value outside 0..2, or an empty texel with a value, is refused (checksums recomputed by
  // writing through the writer's own path is not possible: patch and expect the payload checksum error
  // first, so test the value checks through write + read of a crafted file instead).
  transfer::TransferData bad = small_texel_file(false);
  bad.values[0] = 1.0f;  // texel 0 is empty
  transfer::write_transfer(dir + "/bad.prt", bad);
  CHECK(error_of([&] { transfer::read_transfer(dir + "/bad.prt"); }).find("empty texel 0 has a non-zero value") != std::string::npos);
  bad = small_texel_file(false);
  bad.coverage[4] = 3;
  transfer::write_transfer(dir + "/bad3.prt", bad);
  CHECK(error_of([&] { transfer::read_transfer(dir + "/bad3.prt"); }).find("coverage of texel 4 is 3") != std::string::npos);
  // Truncation and flipped payload bytes.
  std::string bytes = read_bytes(dir + "/t.prt");
  write_bytes(dir + "/cut.prt", bytes.substr(0, bytes.size() - 4));
  CHECK(error_of([&] { transfer::read_transfer(dir + "/cut.prt"); }).find("truncated") != std::string::npos);
  bytes[113] ^= 1;
  write_bytes(dir + "/flip.prt", bytes);
  CHECK(error_of([&] { transfer::read_transfer(dir + "/flip.prt"); }).find("checksum") != std::string::npos);
  // Glossy kinds and sizes out of range cannot be written.
  bad = small_texel_file(false);
  bad.header.texel_width = 16385;
  CHECK(error_of([&] { transfer::write_transfer(dir + "/big.prt", bad); }).find("out of range 1..16384") != std::string::npos);
}

TEST_CASE("lightmap UVs from OBJ vt (v flipped), glTF TEXCOORD_1 before TEXCOORD_0, PLY u, v", "[lightmap][mesh]") {
  const std::string dir = test::fresh_temp_dir("lightmap_uv_loading");
  // OBJ: vt v = 0.25 becomes 0.75; corners follow the face's vt indices.
  write_bytes(dir + "/a.obj", "v 0 0 0\nv 1 0 0\nv 0 0 -1\nvt 0.1 0.25\nvt 0.9 0.25\nvt 0.1 0.8\nf 1/1 2/2 3/3\n");
  mesh::LoadReport report;
  mesh::Mesh m = mesh::load_mesh(dir + "/a.obj", &report, true);
  REQUIRE(m.lightmap_uv.size() == 3);
  CHECK(m.lightmap_uv[0] == glm::vec2(0.1f, 1.0f - 0.25f));
  CHECK(m.lightmap_uv[1] == glm::vec2(0.9f, 1.0f - 0.25f));
  CHECK(m.lightmap_uv[2] == glm::vec2(0.1f, 1.0f - 0.8f));
  CHECK(report.missing_uv_reason.empty());
  // A quad is fan-triangulated with its corners' UVs.
  write_bytes(dir + "/q.obj", "v 0 0 0\nv 1 0 0\nv 1 0 -1\nv 0 0 -1\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3 4/4\n");
  m = mesh::load_mesh(dir + "/q.obj", nullptr, true);
  REQUIRE(m.lightmap_uv.size() == 6);
  CHECK(m.lightmap_uv[3] == glm::vec2(0, 1));
  CHECK(m.lightmap_uv[5] == glm::vec2(0, 0));
  // No vt: no UVs, and the reason.
  write_bytes(dir + "/n.obj", "v 0 0 0\nv 1 0 0\nv 0 0 -1\nf 1 2 3\n");
  m = mesh::load_mesh(dir + "/n.obj", &report, true);
  CHECK(m.lightmap_uv.empty());
  CHECK(report.missing_uv_reason == "the OBJ file has no vt lines");
  // PLY u, v per vertex, v flipped.
  write_bytes(dir + "/a.ply",
              "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nproperty float s\n"
              "property float t\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0 0.5 0.5\n1 0 0 1 0.5\n"
              "0 0 -1 0.5 0\n3 0 1 2\n");
  m = mesh::load_mesh(dir + "/a.ply", nullptr, true);
  REQUIRE(m.lightmap_uv.size() == 3);
  CHECK(m.lightmap_uv[2] == glm::vec2(0.5f, 1.0f));
  // glTF: TEXCOORD_1 is preferred; used as stored (v down).
  std::string bin;
  auto put = [&bin](float f) { bin.append(reinterpret_cast<const char*>(&f), 4); };
  for (float f : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 0.f, -1.f}) put(f);  // POSITION
  for (float f : {0.f, 0.f, 1.f, 0.f, 0.f, 1.f}) put(f);                   // TEXCOORD_0
  for (float f : {0.2f, 0.3f, 0.4f, 0.3f, 0.2f, 0.6f}) put(f);             // TEXCOORD_1
  write_bytes(dir + "/t.bin", bin);
  write_bytes(dir + "/t.gltf", R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
    "meshes":[{"primitives":[{"attributes":{"POSITION":0,"TEXCOORD_0":1,"TEXCOORD_1":2}}]}],
    "buffers":[{"uri":"t.bin","byteLength":84}],
    "bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":24},{"buffer":0,"byteOffset":60,"byteLength":24}],
    "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,-1],"max":[1,0,0]},
                 {"bufferView":1,"componentType":5126,"count":3,"type":"VEC2"},{"bufferView":2,"componentType":5126,"count":3,"type":"VEC2"}]})");
  m = mesh::load_mesh(dir + "/t.gltf", nullptr, true);
  REQUIRE(m.lightmap_uv.size() == 3);
  CHECK(m.lightmap_uv_set == 1);
  CHECK(m.lightmap_uv[1] == glm::vec2(0.4f, 0.3f));
}

TEST_CASE("prt bake --lightmap: byte-identical for 1 and 2 threads - prt info reads it", "[lightmap][cli]") {
  const std::string dir = test::fresh_temp_dir("lightmap_threads");
  test::write_obj_with_uv(dir + "/s.obj", test::floor_and_box(true, -0.1f));
  const std::string common = "bake " + dir + "/s.obj --lightmap 40x24 --transfer interreflected --bounces 2 --samples 64 --quiet ";
  REQUIRE(test::run_prt(common + "--threads 1 -o " + dir + "/a.prt").exit_code == 0);
  REQUIRE(test::run_prt(common + "--threads 2 -o " + dir + "/b.prt").exit_code == 0);
  CHECK(read_bytes(dir + "/a.prt") == read_bytes(dir + "/b.prt"));
  const test::RunResult info = test::run_prt("info " + dir + "/a.prt");
  CHECK(info.exit_code == 0);
  CHECK(info.output.find("lightmap: 40x24 texels (UV set 0") != std::string::npos);
  CHECK(info.output.find("bounce-only section: yes (version 4)") != std::string::npos);
}

TEST_CASE("prt bake --lightmap: bad input gives one line, exit 1 and no file", "[lightmap][cli]") {
  const std::string dir = test::fresh_temp_dir("lightmap_errors");
  const mesh::Mesh good = test::floor_and_box(true);
  test::write_obj_with_uv(dir + "/good.obj", good);
  mesh::Mesh outside = good, overlap = good, collapsed = good;
  outside.lightmap_uv[4].x = 1.5f;                                       // triangle 1
  for (int k = 0; k < 6; ++k) overlap.lightmap_uv[12 + k] = overlap.lightmap_uv[k];  // triangles 4, 5 onto the floor's
  collapsed.lightmap_uv[3 * 6 + 1] = collapsed.lightmap_uv[3 * 6];         // triangle 6
  test::write_obj_with_uv(dir + "/outside.obj", outside);
  test::write_obj_with_uv(dir + "/overlap.obj", overlap);
  test::write_obj_with_uv(dir + "/collapsed.obj", collapsed);
  write_bytes(dir + "/nouv.obj", "v 0 0 0\nv 1 0 0\nv 0 0 -1\nf 1 2 3\n");
  const std::string out = " -o " + dir + "/out.prt --quiet";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"bake " + dir + "/outside.obj --lightmap 32" + out, "outside.obj: lightmap UVs: 1 triangle has UVs outside [0,1] (e.g. triangle 1)"},
      {"bake " + dir + "/overlap.obj --lightmap 32" + out, "overlapping charts"},
      {"bake " + dir + "/overlap.obj --lightmap 32" + out, "(e.g. triangles 0 and 4"},
      {"bake " + dir + "/collapsed.obj --lightmap 32" + out, "1 triangle is collapsed to zero UV area (e.g. triangle 6)"},
      {"bake " + dir + "/nouv.obj --lightmap 32" + out, "nouv.obj: has no lightmap UVs (the OBJ file has no vt lines)"},
      {"bake " + dir + "/good.obj --lightmap 0" + out, "--lightmap 0: each side must be 1..16384"},
      {"bake " + dir + "/good.obj --lightmap 64x0" + out, "--lightmap 64x0"},
      {"bake " + dir + "/good.obj --lightmap 20000" + out, "1..16384"},
      {"bake " + dir + "/good.obj --lightmap 8x" + out, "expected WxH or SIZE"},
      {"bake " + dir + "/good.obj --lightmap 16384 --bands 32" + out, "needs about"},
      {"bake " + dir + "/good.obj --lightmap 32 --gutter 65" + out, "--gutter 65"},
      {"bake " + dir + "/good.obj --lightmap 32 --transfer glossy-shadowed --brdf phong:exponent=8" + out, "glossy"},
  };
  const std::size_t before = test::entries_in(dir);
  for (const auto& [arguments, needle] : cases) {
    const test::RunResult r = test::run_prt(arguments);
    INFO(arguments << "\n" << r.output);
    CHECK(test::fails_in_one_line(r, needle));
    CHECK(r.output.rfind("prt: ", 0) == 0);
    CHECK(test::entries_in(dir) == before);
  }
  // The good mesh bakes (so the errors above are the inputs' own).
  CHECK(test::run_prt("bake " + dir + "/good.obj --lightmap 32 --samples 16" + out).exit_code == 0);
  // prt shade refuses a lightmap without --lightmap and a vertex file with it.
  const test::RunResult s = test::run_prt("shade " + dir + "/good.obj " + dir + "/out.prt --env constant:1,1,1 -o " + dir + "/x.ply");
  CHECK(test::fails_in_one_line(s, "is a lightmap"));
  // A per-vertex file where a lightmap is needed.
  REQUIRE(test::run_prt("bake " + dir + "/good.obj --samples 16 --quiet -o " + dir + "/vertex.prt").exit_code == 0);
  std::size_t files = test::entries_in(dir);
  CHECK(test::fails_in_one_line(
      test::run_prt("shade " + dir + "/good.obj " + dir + "/vertex.prt --env constant:1,1,1 --lightmap -o " + dir + "/x.exr"),
      "--lightmap needs a lightmap"));
  test::write_test_sky(dir + "/sky.exr");
  files = test::entries_in(dir);
  CHECK(test::fails_in_one_line(test::run_prt("reference " + dir + "/good.obj --env " + dir + "/sky.exr --samples 4 --quiet --texels " + dir +
                                              "/vertex.prt -o " + dir + "/x.exr"),
                                "not a lightmap"));
  CHECK(test::entries_in(dir) == files);
}

}  // namespace prt
