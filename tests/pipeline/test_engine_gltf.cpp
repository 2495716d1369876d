// The engine glTF of `prt bake --gltf` (docs/formats.md, "The engine glTF: PRT_transfer"), through the
// real binary on third-party glTF (BoxTextured, Khronos sample, CC-BY 4.0; 2CylinderEngine, Khronos
// sample from Debian's assimp-testmodels; a Draco box) and an OBJ with two materials:
// - the file is read here with this test's own GLB parser (not prt's), by the layout formats.md states:
//   the source's nodes (transforms as authored), materials, textures, samplers and images are kept, at
//   most 16 attributes per primitive, the model equals the .cprt's bit for bit, and the per-vertex
//   radiance decoded here from the file equals the .cprt's decompression under a random sky;
// - prt reads it back (open_transfer, load_mesh): the same mesh as the source (fingerprint, albedo) and
//   the same transfer as the .cprt; `prt shade` gives the same bytes from the .glb as from the .cprt;
// - bad input: a glb without the extension, a cluster index out of range, 17 attributes: one line.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <map>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "compress/cprt_file.h"
#include "compress/open_transfer.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "mesh/engine_gltf.h"
#include "mesh/mesh.h"
#include "glb_reader.h"
#include "support/run_prt.h"

using namespace prt;
using nlohmann::json;

namespace {

const std::string kBox = std::string(PRT_SOURCE_DIR) + "/tests/data/BoxTextured/BoxTextured.glb";
const std::string kDraco = std::string(PRT_SOURCE_DIR) + "/tests/data/gltf/box_textured_draco.glb";
// SH lighting (prt light of sunrise.exr, 5 bands).
const std::string kLight = std::string(PRT_SOURCE_DIR) + "/tests/data/golden_light_sunrise_b5.json";
const std::string kEngine = "/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb";

using test::Glb;
using test::floats;
using test::parse_glb;

// Visits the triangle primitives of the default scene in the order formats.md ("Vertex order") gives:
// nodes depth-first, each before its children, a node's mesh's primitives in order.
void each_primitive(const json& doc, const std::function<void(const json& node, const json& primitive)>& f) {
  std::function<void(int)> visit = [&](int n) {
    const json& node = doc["nodes"][n];
    if (node.contains("mesh"))
      for (const json& p : doc["meshes"][node["mesh"].get<int>()]["primitives"])
        if (p.value("mode", 4) >= 4) f(node, p);
    for (const json& child : node.value("children", json::array())) visit(child.get<int>());
  };
  for (const json& root : doc["scenes"][doc.value("scene", 0)]["nodes"]) visit(root.get<int>());
}

// The radiance per vertex (RGB) that the file's model gives under `sky` (C B^2 coefficients per
// channel, prt basis), by formats.md's shading rule, computed in double.
std::vector<double> glb_radiance(const Glb& g, const std::vector<double>& sky) {
  const json& m = g.doc["extensions"]["PRT_transfer"]["models"][0];
  const int k_count = m["clusters"], n = m["terms"], b = m["bands"], c_count = m["channels"];
  const std::size_t d = std::size_t(c_count * b * b), dp = m["bounce"].get<bool>() ? 2 * d : d;
  const std::vector<float> means = floats(g, m["means"]), bases = floats(g, m["bases"]);
  REQUIRE(means.size() == std::size_t(k_count) * dp);
  REQUIRE(bases.size() == std::size_t(k_count * n) * dp);
  std::vector<double> out;
  each_primitive(g.doc, [&](const json&, const json& p) {
    const json& at = p["attributes"];
    const std::vector<float> cluster = floats(g, at["_PRT_CLUSTER"]);
    std::vector<std::vector<float>> weights;
    for (int a = 0; 4 * a < n; ++a) weights.push_back(floats(g, at["_PRT_WEIGHTS" + std::to_string(a)]));
    for (std::size_t v = 0; v < cluster.size(); ++v) {
      const std::size_t k = std::size_t(cluster[v]);
      for (int ch = 0; ch < 3; ++ch) {
        const std::size_t tc = c_count == 1 ? 0 : std::size_t(ch);
        double sum = 0.0;
        for (std::size_t i = 0; i < std::size_t(b * b); ++i) {
          double t = means[k * dp + tc * std::size_t(b * b) + i];
          for (int j = 0; j < n; ++j) t += weights[std::size_t(j / 4)][4 * v + std::size_t(j % 4)] * bases[(k * std::size_t(n) + std::size_t(j)) * dp + tc * std::size_t(b * b) + i];
          sum += t * sky[std::size_t(ch) * std::size_t(b * b) + i];
        }
        out.push_back(sum);
      }
    }
  });
  return out;
}

std::vector<double> transfer_radiance(const transfer::TransferData& t, const std::vector<double>& sky) {
  const std::size_t bb = std::size_t(t.header.bands) * t.header.bands, d = t.header.values_per_vertex();
  std::vector<double> out;
  for (std::size_t v = 0; v < t.header.vertex_count; ++v)
    for (std::size_t ch = 0; ch < 3; ++ch) {
      const std::size_t tc = t.header.channels == 1 ? 0 : ch;
      double sum = 0.0;
      for (std::size_t i = 0; i < bb; ++i) sum += double(t.values[v * d + tc * bb + i]) * sky[ch * bb + i];
      out.push_back(sum);
    }
  return out;
}

double rel_rms(const std::vector<double>& a, const std::vector<double>& ref) {
  REQUIRE(a.size() == ref.size());
  double e = 0.0, n = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    e += (a[i] - ref[i]) * (a[i] - ref[i]);
    n += ref[i] * ref[i];
  }
  return std::sqrt(e / n);
}

struct Export {
  std::string glb, cprt;
};

Export bake(const std::string& source, const std::string& dir, const std::string& name, const std::string& compress = "16,4") {
  Export e{dir + "/" + name + ".glb", dir + "/" + name + ".cprt"};
  const test::RunResult r = test::run_prt("bake " + source + " --transfer interreflected --bands 3 --samples 64 --bounces 1 "
                                          "--compress " + compress + " --threads 2 -q -o " + e.cprt + " --gltf " + e.glb);
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  return e;
}

// What every export must satisfy against its glTF source, read with this file's own parser.
void check_against_source(const Export& e, const std::string& source) {
  const Glb out = parse_glb(e.glb), in = parse_glb(source);
  INFO(e.glb);
  for (const char* list : {"nodes", "materials", "textures", "samplers", "images", "scenes"})
    CHECK(out.doc.value(list, json::array()).size() == in.doc.value(list, json::array()).size());
  for (std::size_t n = 0; n < in.doc["nodes"].size(); ++n)
    for (const char* key : {"matrix", "translation", "rotation", "scale", "children", "name"})
      CHECK(out.doc["nodes"][n].value(key, json()) == in.doc["nodes"][n].value(key, json()));
  CHECK(out.doc["materials"] == in.doc["materials"]);
  CHECK(out.doc["extensionsUsed"].back() == "PRT_transfer");
  CHECK(!out.doc.value("extensionsRequired", json::array()).contains("PRT_transfer"));
  for (const char* dropped : {"KHR_draco_mesh_compression", "EXT_meshopt_compression"})
    CHECK(std::find(out.doc["extensionsUsed"].begin(), out.doc["extensionsUsed"].end(), dropped) == out.doc["extensionsUsed"].end());
  std::size_t primitives = 0;
  for (const json& mesh : out.doc["meshes"])
    for (const json& p : mesh["primitives"]) {
      CHECK(p["attributes"].size() <= 16);
      ++primitives;
    }
  CHECK(primitives > 0);
  // The images are the source's bytes.
  for (std::size_t i = 0; i < out.doc.value("images", json::array()).size(); ++i) {
    const json& view = out.doc["bufferViews"][out.doc["images"][i]["bufferView"].get<int>()];
    const std::string bytes = out.bin.substr(view.value("byteOffset", 0), view["byteLength"]);
    if (in.doc["images"][i].contains("bufferView")) {
      const json& v = in.doc["bufferViews"][in.doc["images"][i]["bufferView"].get<int>()];
      CHECK(bytes == in.bin.substr(v.value("byteOffset", 0), v["byteLength"]));
    }
  }
}

// The file's model equals the .cprt's, its shading equals the .cprt's, and prt reads it back as the source.
void check_transfer(const Export& e, const std::string& source) {
  INFO(e.glb);
  const compress::CompressedTransfer cprt = compress::read_cprt(e.cprt);
  const Glb g = parse_glb(e.glb);
  const json& m = g.doc["extensions"]["PRT_transfer"]["models"][0];
  CHECK(m["clusters"] == cprt.clusters);
  CHECK(m["terms"] == cprt.pca);
  CHECK(m["bounce"] == cprt.bounce);
  CHECK(floats(g, m["means"]) == cprt.means);
  CHECK(floats(g, m["bases"]) == cprt.bases);

  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  std::vector<double> sky(3 * std::size_t(cprt.source.bands * cprt.source.bands));
  for (double& x : sky) x = normal(rng);
  const transfer::TransferData decompressed = compress::decompress(cprt);
  CHECK(rel_rms(glb_radiance(g, sky), transfer_radiance(decompressed, sky)) < 1e-6);

  const mesh::Mesh from_glb = mesh::load_mesh(e.glb, nullptr, true), from_source = mesh::load_mesh(source, nullptr, true);
  CHECK(mesh::fingerprint(from_glb) == mesh::fingerprint(from_source));
  CHECK(from_glb.albedo == from_source.albedo);
  compress::TransferFile file = compress::open_transfer(e.glb);
  CHECK(file.baked_albedo == from_source.albedo);
  const transfer::TransferData back = compress::expand(std::move(file));
  CHECK(back.values == decompressed.values);
  CHECK(back.bounce_only == decompressed.bounce_only);
}

}  // namespace

TEST_CASE("Engine glTF of third-party glTF keeps the scene and carries the .cprt's model", "[pipeline][gltf][cli]") {
  const std::string dir = test::fresh_temp_dir("engine_gltf");
  for (const std::string& source : {kBox, kDraco}) {
    const Export e = bake(source, dir, std::filesystem::path(source).stem().string());
    check_against_source(e, source);
    check_transfer(e, source);
  }
}

TEST_CASE("Engine glTF of 2CylinderEngine: instanced meshes get a copy per baked node", "[pipeline][gltf][cli][slow]") {
  if (!std::filesystem::exists(kEngine)) {
    WARN("skipped: " + kEngine + " (Debian package assimp-testmodels) is not installed");
    return;
  }
  const std::string dir = test::fresh_temp_dir("engine_gltf_2cyl");
  const Export e = bake(kEngine, dir, "engine");
  check_against_source(e, kEngine);
  check_transfer(e, kEngine);
  // Every node instance with a mesh has a mesh no other node uses.
  const Glb g = parse_glb(e.glb);
  std::map<int, int> users;
  for (const json& node : g.doc["nodes"])
    if (node.contains("mesh")) ++users[node["mesh"].get<int>()];
  for (const auto& [mesh, count] : users) CHECK(count == 1);
  CHECK(g.doc["meshes"].size() >= parse_glb(kEngine).doc["meshes"].size());
}

TEST_CASE("prt shade reads the engine glTF as mesh and transfer: the same bytes as from the .cprt", "[pipeline][gltf][cli]") {
  const std::string dir = test::fresh_temp_dir("engine_gltf_shade");
  const Export e = bake(kBox, dir, "box");
  const test::RunResult a = test::run_prt("shade " + e.glb + " " + e.glb + " --light " + kLight + " -o " + dir + "/a.ply");
  const test::RunResult b = test::run_prt("shade " + kBox + " " + e.cprt + " --light " + kLight + " -o " + dir + "/b.ply");
  INFO(a.output << b.output);
  REQUIRE(a.exit_code == 0);
  REQUIRE(b.exit_code == 0);
  CHECK(read_file(dir + "/a.ply") == read_file(dir + "/b.ply"));
}

TEST_CASE("Engine glTF of an OBJ with two materials: one primitive per material", "[pipeline][gltf][cli]") {
  const std::string dir = test::fresh_temp_dir("engine_gltf_obj");
  write_file_atomically(dir + "/two.mtl", "newmtl red\nKd 0.8 0.1 0.1\nnewmtl blue\nKd 0.1 0.2 0.7\n");
  // A floor (red) and a box-like wall (blue) sharing an edge.
  write_file_atomically(dir + "/two.obj",
                        "mtllib two.mtl\nv -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nv -1 1 -1\nv 1 1 -1\n"
                        "usemtl red\nf 1 3 2\nf 1 4 3\nusemtl blue\nf 1 2 6\nf 1 6 5\n");
  const Export e = bake(dir + "/two.obj", dir, "two", "3,2");
  const Glb g = parse_glb(e.glb);
  REQUIRE(g.doc["meshes"].size() == 1);
  REQUIRE(g.doc["meshes"][0]["primitives"].size() == 2);
  const json& red = g.doc["materials"][g.doc["meshes"][0]["primitives"][0]["material"].get<int>()];
  const json& blue = g.doc["materials"][g.doc["meshes"][0]["primitives"][1]["material"].get<int>()];
  CHECK(red["name"] == "red");
  CHECK(blue["name"] == "blue");
  CHECK(blue["pbrMetallicRoughness"]["baseColorFactor"][2].get<double>() == Approx(0.7));
  // The shared edge's two vertices are in both primitives: 4 + 4 glTF vertices for 6 OBJ vertices.
  CHECK(floats(g, g.doc["meshes"][0]["primitives"][0]["attributes"]["_PRT_CLUSTER"]).size() == 4);
  // The radiance per glTF vertex is the .cprt's of the OBJ vertex it stands for (positions match).
  const compress::CompressedTransfer cprt = compress::read_cprt(e.cprt);
  std::vector<double> sky(3 * 9, 0.0);
  sky[0] = sky[9] = sky[18] = 1.0;
  sky[2] = 0.5;
  const std::vector<double> from_glb = glb_radiance(g, sky), from_cprt = transfer_radiance(compress::decompress(cprt), sky);
  const mesh::Mesh obj = mesh::load_mesh(dir + "/two.obj", nullptr, true);
  std::size_t at = 0;
  for (const json& p : g.doc["meshes"][0]["primitives"]) {
    const std::vector<float> pos = floats(g, p["attributes"]["POSITION"]);
    for (std::size_t v = 0; v < pos.size() / 3; ++v, ++at) {
      std::size_t source = 0;
      while (obj.positions[source] != glm::vec3(pos[3 * v], pos[3 * v + 1], pos[3 * v + 2])) ++source;
      for (int c = 0; c < 3; ++c) CHECK(from_glb[3 * at + std::size_t(c)] == Approx(from_cprt[3 * source + std::size_t(c)]).epsilon(1e-6));
    }
  }
}

TEST_CASE("Bad engine glTF input is one line naming the file", "[pipeline][gltf][cli]") {
  const std::string dir = test::fresh_temp_dir("engine_gltf_bad");
  // A glTF without PRT_transfer holds no transfer.
  CHECK_THROWS_WITH(compress::open_transfer(kBox), Catch::Contains(kBox + ": a glTF without the PRT_transfer extension"));
  // A cluster index out of range.
  const Export e = bake(kBox, dir, "box");
  Glb g = parse_glb(e.glb);
  const int accessor = g.doc["meshes"][0]["primitives"][0]["attributes"]["_PRT_CLUSTER"];
  const json& view = g.doc["bufferViews"][g.doc["accessors"][accessor]["bufferView"].get<int>()];
  std::string bytes = read_file(e.glb);
  const std::uint32_t json_length = [&] { std::uint32_t v; std::memcpy(&v, bytes.data() + 12, 4); return v; }();
  const float bad = 1e6f;
  std::memcpy(&bytes[28 + json_length + view.value("byteOffset", 0)], &bad, 4);
  write_file_atomically(dir + "/bad.glb", bytes);
  const test::RunResult r = test::run_prt("shade " + dir + "/bad.glb " + dir + "/bad.glb --light " + kLight + " -o " + dir + "/bad.ply");
  CHECK(test::fails_in_one_line(r, dir + "/bad.glb: _PRT_CLUSTER: a value is not a cluster index"));
  CHECK(!std::filesystem::exists(dir + "/bad.ply"));
  // More than 16 attributes per primitive: refused, no file.
  const mesh::Mesh box = mesh::load_mesh(kBox, nullptr, true);
  mesh::EngineExtras extras;
  for (int a = 0; a < 14; ++a)
    extras.attributes.push_back({"_X" + std::to_string(a), 1, std::vector<float>(box.vertex_count(), 0.0f)});
  extras.extension = "PRT_test";
  extras.root = [](const mesh::EngineIndices&) { return json::object(); };
  extras.primitive = [](const mesh::EngineIndices&, int) { return json::object(); };
  CHECK_THROWS_WITH(mesh::write_engine_glb(dir + "/many.glb", kBox, box, extras), Catch::Contains("more than 16"));
  CHECK(!std::filesystem::exists(dir + "/many.glb"));
  extras.attributes.pop_back();  // 16 (POSITION, NORMAL, TEXCOORD_0 and 13) is allowed
  mesh::write_engine_glb(dir + "/sixteen.glb", kBox, box, extras);
  CHECK(parse_glb(dir + "/sixteen.glb").doc["meshes"][0]["primitives"][0]["attributes"].size() == 16);
}

TEST_CASE("Per-texel engine glTF: KTX2 cluster and weights textures, read back as the .cprt's model", "[pipeline][gltf][cli][lightmap]") {
  const std::string dir = test::fresh_temp_dir("engine_gltf_texel");
  // An OBJ floor and wall with one UV chart each (vt in [0, 1], no overlaps), and, when installed,
  // Khronos's BoxTexcoords (TEXCOORD_1 as the lightmap set).
  write_file_atomically(dir + "/lm.obj",
                        "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nv -1 0 -1\nv 1 0 -1\nv 1 1 -1\nv -1 1 -1\n"
                        "vt 0.05 0.05\nvt 0.45 0.05\nvt 0.45 0.45\nvt 0.05 0.45\nvt 0.55 0.55\nvt 0.95 0.55\nvt 0.95 0.95\nvt 0.55 0.95\n"
                        "f 1/1 4/4 3/3\nf 1/1 3/3 2/2\nf 5/5 6/6 7/7\nf 5/5 7/7 8/8\n");
  std::vector<std::string> sources{dir + "/lm.obj"};
  const std::string texcoords = "/usr/share/assimp/models/glTF2/BoxTexcoords-glTF/boxTexcoords.gltf";
  if (std::filesystem::exists(texcoords)) sources.push_back(texcoords);
  for (const std::string& source : sources) {
    INFO(source);
    const std::string out = dir + "/" + std::filesystem::path(source).stem().string();
    const test::RunResult r = test::run_prt("bake " + source + " --lightmap 16 --transfer interreflected --bands 3 --samples 32 "
                                            "--bounces 1 --compress 6,4 -q -o " + out + ".cprt --gltf " + out + ".glb");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    const Glb g = parse_glb(out + ".glb");
    for (const json& mesh : g.doc["meshes"])
      for (const json& p : mesh["primitives"]) {
        const json& ext = p["extensions"]["PRT_transfer"];
        CHECK(ext["width"] == 16);
        CHECK(p["attributes"].contains("TEXCOORD_" + std::to_string(ext["texCoord"].get<int>())));
        CHECK(p["attributes"].size() <= 16);
        CHECK(g.doc["images"][ext["cluster"].get<int>()]["mimeType"] == "image/ktx2");
      }
    // prt's reader against the .cprt: the same points, clusters and means; weights to float16 rounding.
    const compress::CompressedTransfer cprt = compress::read_cprt(out + ".cprt");
    compress::TransferFile file = compress::open_transfer(out + ".glb");
    const auto& back = std::get<compress::CompressedTransfer>(file.contents);
    CHECK(back.coverage == cprt.coverage);
    CHECK(back.cluster == cprt.cluster);
    CHECK(back.means == cprt.means);
    CHECK(back.bases == cprt.bases);
    REQUIRE(back.weights.size() == cprt.weights.size());
    for (std::size_t i = 0; i < cprt.weights.size(); ++i)
      CHECK(std::fabs(back.weights[i] - cprt.weights[i]) <= std::ldexp(std::fabs(cprt.weights[i]), -11) + 1e-7f);
    REQUIRE(test::run_prt("shade " + out + ".glb " + out + ".glb --lightmap --light " + kLight + " -o " + out + "_a.exr").exit_code == 0);
    REQUIRE(test::run_prt("shade " + source + " " + out + ".cprt --lightmap --light " + kLight + " -o " + out + "_b.exr").exit_code == 0);
    CHECK(test::compare_rel_rms(out + "_a.exr", out + "_b.exr") < 1e-3);
  }
}

TEST_CASE("The engine glTF is byte-identical for any thread count", "[pipeline][gltf][cli]") {
  const std::string dir = test::fresh_temp_dir("engine_gltf_threads");
  std::string bytes[2];
  for (int threads : {1, 3}) {
    const std::string out = dir + "/t" + std::to_string(threads);
    const test::RunResult r = test::run_prt("bake " + kBox + " --transfer interreflected --bands 3 --samples 32 --bounces 1 -q --threads " +
                                            std::to_string(threads) + " -o " + out + ".prt --gltf " + out + ".glb");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    bytes[threads == 1 ? 0 : 1] = read_file(out + ".glb");
  }
  CHECK(bytes[0].size() > 1000);
  CHECK(bytes[0] == bytes[1]);
}

TEST_CASE("Per-texel engine glTF with generated lightmap UVs carries them as TEXCOORD_1", "[pipeline][gltf][cli][lightmap]") {
  // BoxTextured's UVs leave [0, 1]: prt bake --uv auto generates lightmap UVs, which the export must carry
  // (as the mesh loaded: one node, TEXCOORD_0 the base colour UVs with the embedded PNG, TEXCOORD_1 the
  // generated ones), so that prt shade reads the .glb alone as mesh and transfer.
  const std::string dir = test::fresh_temp_dir("engine_gltf_uv");
  const std::string out = dir + "/box";
  const test::RunResult r = test::run_prt("bake " + kBox + " --lightmap 32 --uv auto --transfer shadowed --bands 3 --samples 16 "
                                          "--compress 4,2 -q -o " + out + ".cprt --gltf " + out + ".glb");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  const Glb g = parse_glb(out + ".glb");
  const json& p = g.doc["meshes"][0]["primitives"][0];
  CHECK(p["extensions"]["PRT_transfer"]["texCoord"] == 1);
  CHECK(p["attributes"].contains("TEXCOORD_1"));
  CHECK(g.doc["images"][g.doc["textures"][0]["source"].get<int>()]["mimeType"] == "image/png");
  const test::RunResult a = test::run_prt("shade " + out + ".glb " + out + ".glb --lightmap --light " + kLight + " -o " + out + "_a.exr");
  INFO(a.output);
  REQUIRE(a.exit_code == 0);
  const compress::CompressedTransfer cprt = compress::read_cprt(out + ".cprt");
  compress::TransferFile file = compress::open_transfer(out + ".glb");
  CHECK(std::get<compress::CompressedTransfer>(file.contents).coverage == cprt.coverage);
  CHECK(std::get<compress::CompressedTransfer>(file.contents).cluster == cprt.cluster);
}
