// The engine glTF of a mixed scene (`prt bake --lightmap N --texel-parts ... --gltf`; docs/formats.md,
// "Mixed scenes" under the engine glTF), through the real binary on the room of tests/lightmap
// (floor and back wall per texel, a box and a ball standing on the floor per vertex), read with this
// test's own GLB and KTX2 parsers by the layout formats.md states:
// - two models, model 0 per texel and model 1 per vertex; every primitive of the Floor and Wall nodes
//   is a per-texel primitive (KTX2 images, its TEXCOORD set, _PRT_ALBEDO, no _PRT_CLUSTER), every Box
//   and Ball primitive a per-vertex one (_PRT_CLUSTER, _PRT_WEIGHTSn, _PRT_ALBEDO);
// - the radiance decoded here from the file (formats.md's CPCA rule) under random skies against the
//   .prt pair's own values: per vertex over the Box's vertices, per texel over the covered texels;
// - with generated UVs (--uv generate): the file is written from ROOM.mesh.glb, each primitive of one
//   kind, its per-vertex primitives against the per-vertex file;
// - the same bytes for 1 and 3 threads; bad input: prt's readers refuse the file (one line naming the
//   primitive that uses model 1), and a failing write leaves none of the outputs.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "lightmap/mixed_scenes.h"
#include "glb_reader.h"
#include "support/run_prt.h"
#include "support/shapes.h"
#include "transfer/transfer_file.h"

using namespace prt;
using nlohmann::json;

namespace {

// SH lighting (prt light of sunrise.exr, 5 bands).
const std::string kLight = std::string(PRT_SOURCE_DIR) + "/tests/data/golden_light_sunrise_b5.json";

using test::Glb;
using test::floats;
using test::parse_glb;
using test::view_bytes;

std::uint32_t u32(const std::string& b, std::size_t at) {
  std::uint32_t v;
  std::memcpy(&v, b.data() + at, 4);
  return v;
}

// IEEE binary16 to float.
float half_to_float(std::uint16_t h) {
  const int exponent = (h >> 10) & 0x1f, fraction = h & 0x3ff;
  const float sign = (h & 0x8000) ? -1.0f : 1.0f;
  if (exponent == 0) return sign * std::ldexp(float(fraction), -24);
  REQUIRE(exponent != 31);
  return sign * std::ldexp(1.0f + float(fraction) / 1024.0f, exponent - 15);
}

// A KTX 2.0 RGBA16F image (one level, no supercompression) by the KTX 2.0 specification's layout: its
// texels as floats, layer-major, rows top first.
struct Ktx {
  std::uint32_t width = 0, height = 0, layers = 0;
  std::vector<float> rgba;
};

Ktx parse_ktx2(const std::string& b) {
  REQUIRE(b.compare(0, 12, std::string("\xABKTX 20\xBB\r\n\x1A\n", 12)) == 0);
  REQUIRE(u32(b, 12) == 97);  // VK_FORMAT_R16G16B16A16_SFLOAT
  REQUIRE(u32(b, 44) == 0);   // no supercompression
  Ktx k{u32(b, 20), u32(b, 24), u32(b, 32), {}};
  std::uint64_t offset, length;
  std::memcpy(&offset, b.data() + 80, 8);
  std::memcpy(&length, b.data() + 88, 8);
  REQUIRE(length == 8ull * k.width * k.height * std::max(1u, k.layers));
  for (std::uint64_t i = 0; i < length / 2; ++i) {
    std::uint16_t h;
    std::memcpy(&h, b.data() + offset + 2 * i, 2);
    k.rgba.push_back(half_to_float(h));
  }
  return k;
}

// One model of the root extension, read with its arrays.
struct Model {
  int clusters, terms, bands, channels;
  std::size_t dp;  // values per point, bounce part included
  std::vector<float> means, bases;
  // The radiance of channel `ch` of a point of cluster k with weights w under `sky` (formats.md).
  double radiance(std::size_t k, const std::function<float(int)>& w, int ch, const std::vector<double>& sky) const {
    const std::size_t bb = std::size_t(bands * bands), tc = channels == 1 ? 0 : std::size_t(ch);
    double sum = 0.0;
    for (std::size_t i = 0; i < bb; ++i) {
      double t = means[k * dp + tc * bb + i];
      for (int j = 0; j < terms; ++j) t += double(w(j)) * bases[(k * std::size_t(terms) + std::size_t(j)) * dp + tc * bb + i];
      sum += t * sky[std::size_t(ch) * bb + i];
    }
    return sum;
  }
};

Model read_model(const Glb& g, int index) {
  const json& m = g.doc["extensions"]["PRT_transfer"]["models"][index];
  Model out{m["clusters"], m["terms"], m["bands"], m["channels"], 0, floats(g, m["means"]), floats(g, m["bases"])};
  out.dp = std::size_t(out.channels * out.bands * out.bands) * (m["bounce"].get<bool>() ? 2 : 1);
  REQUIRE(out.means.size() == std::size_t(out.clusters) * out.dp);
  REQUIRE(out.bases.size() == std::size_t(out.clusters * out.terms) * out.dp);
  return out;
}

// The .prt's radiance of block b (a vertex or a texel), channel ch, under `sky`.
double prt_radiance(const transfer::TransferData& t, std::size_t b, int ch, const std::vector<double>& sky) {
  const std::size_t bb = std::size_t(t.header.bands) * t.header.bands, d = t.header.values_per_vertex();
  const std::size_t tc = t.header.channels == 1 ? 0 : std::size_t(ch);
  double sum = 0.0;
  for (std::size_t i = 0; i < bb; ++i) sum += double(t.values[b * d + tc * bb + i]) * sky[std::size_t(ch) * bb + i];
  return sum;
}

struct Error2 {
  double err = 0.0, ref = 0.0;
  void add(double a, double b) { err += (a - b) * (a - b), ref += b * b; }
  double rel_rms() const { return std::sqrt(err / ref); }
};

std::vector<double> random_sky(int bands, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  std::vector<double> sky(3 * std::size_t(bands * bands));
  for (double& x : sky) x = normal(rng);
  sky[0] = sky[std::size_t(bands * bands)] = sky[2 * std::size_t(bands * bands)] = 4.0;  // a positive mean, like any sky
  return sky;
}

// Visits the default scene's triangle primitives in prt's load order (formats.md "Vertex order"), with
// the index of their first vertex in that order.
void each_primitive(const json& doc, const std::function<void(const json& node, const json& primitive, std::size_t first)>& f) {
  std::size_t first = 0;
  std::function<void(int)> visit = [&](int n) {
    const json& node = doc["nodes"][n];
    if (node.contains("mesh"))
      for (const json& p : doc["meshes"][node["mesh"].get<int>()]["primitives"]) {
        f(node, p, first);
        first += doc["accessors"][p["attributes"]["POSITION"].get<int>()]["count"].get<std::size_t>();
      }
    for (const json& child : node.value("children", json::array())) visit(child.get<int>());
  };
  for (const json& root : doc["scenes"][doc.value("scene", 0)]["nodes"]) visit(root.get<int>());
}

struct MixedCheck {
  std::size_t texel_primitives = 0, vertex_primitives = 0, vertices = 0, texels = 0;
  double vertex_error = 0.0, texel_error = 0.0;
};

// Checks the layout of every primitive and compares the file's radiance with the pair's under 3 skies.
MixedCheck check_mixed(const std::string& glb, const std::string& prt, const std::string& vertices_prt) {
  INFO(glb);
  const Glb g = parse_glb(glb);
  REQUIRE(g.doc["extensions"]["PRT_transfer"]["models"].size() == 2);
  const Model texel = read_model(g, 0), vertex = read_model(g, 1);
  const transfer::TransferData texel_prt = transfer::read_transfer(prt), vertex_prt = transfer::read_transfer(vertices_prt);
  MixedCheck out;
  Error2 vertex_error, texel_error;
  each_primitive(g.doc, [&](const json&, const json& p, std::size_t first) {
    const json& ext = p["extensions"]["PRT_transfer"];
    const json& at = p["attributes"];
    CHECK(at.contains("_PRT_ALBEDO"));
    CHECK(at.size() <= 16);
    if (ext["model"] == 1) {  // per vertex: its vertices against the per-vertex file's
      ++out.vertex_primitives;
      CHECK(!ext.contains("width"));
      const std::vector<float> cluster = floats(g, at["_PRT_CLUSTER"]);
      std::vector<std::vector<float>> weights;
      for (int a = 0; 4 * a < vertex.terms; ++a) weights.push_back(floats(g, at["_PRT_WEIGHTS" + std::to_string(a)]));
      for (std::size_t v = 0; v < cluster.size(); ++v, ++out.vertices)
        for (unsigned seed : {1u, 2u, 3u}) {
          const std::vector<double> sky = random_sky(vertex.bands, seed);
          for (int ch = 0; ch < 3; ++ch)
            vertex_error.add(vertex.radiance(std::size_t(cluster[v]), [&](int j) { return weights[j / 4][4 * v + j % 4]; }, ch, sky),
                             prt_radiance(vertex_prt, first + v, ch, sky));
        }
      return;
    }
    REQUIRE(ext["model"] == 0);
    ++out.texel_primitives;
    CHECK(!at.contains("_PRT_CLUSTER"));
    CHECK(at.contains("TEXCOORD_" + std::to_string(ext["texCoord"].get<int>())));
    REQUIRE(ext["width"] == texel_prt.header.texel_width);
    REQUIRE(ext["height"] == texel_prt.header.texel_height);
    if (out.texels > 0) return;  // every texel primitive names the same images: compare them once
    const Ktx cluster = parse_ktx2(view_bytes(g, g.doc["images"][ext["cluster"].get<int>()]["bufferView"]));
    const Ktx weights = parse_ktx2(view_bytes(g, g.doc["images"][ext["weights"].get<int>()]["bufferView"]));
    const std::size_t texels = std::size_t(cluster.width) * cluster.height;
    for (std::size_t t = 0; t < texels; ++t) {
      CHECK(cluster.rgba[4 * t + 1] == float(texel_prt.coverage[t]));
      if (texel_prt.coverage[t] == transfer::kTexelEmpty) continue;
      ++out.texels;
      for (unsigned seed : {1u, 2u, 3u}) {
        const std::vector<double> sky = random_sky(texel.bands, seed);
        for (int ch = 0; ch < 3; ++ch)
          texel_error.add(texel.radiance(std::size_t(cluster.rgba[4 * t]), [&](int j) { return weights.rgba[4 * ((j / 4) * texels + t) + j % 4]; },
                                         ch, sky),
                          prt_radiance(texel_prt, t, ch, sky));
      }
    }
  });
  out.vertex_error = vertex_error.rel_rms();
  out.texel_error = texel_error.rel_rms();
  return out;
}

// The room of tests/lightmap (Floor, Box, Wall) with a ball on the floor beside the box, part "Ball"
// (a UV sphere of radius 0.25, 8 x 16: 114 vertices), so that the per-vertex model has fewer clusters
// (64) than vertices and its weights matter. Its UVs (never read per vertex) are one point.
void write_room_with_ball(const std::string& path) {
  std::vector<test::NamedPart> parts;
  mesh::Mesh room = test::room_with_box(true, parts);
  const mesh::Mesh ball = test::uv_sphere(8, 16);
  const std::uint32_t base = std::uint32_t(room.vertex_count());
  for (std::size_t v = 0; v < ball.vertex_count(); ++v) {
    room.positions.push_back(0.25f * ball.positions[v] + glm::vec3(0.6f, 0.25f, -0.5f));
    room.normals.push_back(ball.normals[v]);
  }
  parts.push_back({"Ball", room.triangle_count(), ball.triangle_count()});
  for (std::uint32_t i : ball.indices) room.indices.push_back(base + i), room.lightmap_uv.push_back(glm::vec2(0.5f));
  test::write_gltf_parts(path, room, parts);
}

std::string bake_command(const std::string& scene, const std::string& out, const std::string& extra) {
  return "bake " + scene + " --lightmap 32 --texel-parts Floor,Wall --transfer interreflected --bands 3 --samples 64 --bounces 1 -q " +
         extra + " -o " + out + ".prt --gltf " + out + ".glb";
}

}  // namespace

TEST_CASE("Mixed engine glTF: per-texel Floor and Wall, per-vertex Box and Ball, each as its .prt file", "[pipeline][gltf][cli][mixed]") {
  const std::string dir = test::fresh_temp_dir("engine_gltf_mixed");
  write_room_with_ball(dir + "/room.gltf");
  const test::RunResult r = test::run_prt(bake_command(dir + "/room.gltf", dir + "/m", "--threads 1"));
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  const MixedCheck c = check_mixed(dir + "/m.glb", dir + "/m.prt", dir + "/m.vertices.prt");
  CHECK(c.texel_primitives == 2);
  CHECK(c.vertex_primitives == 2);
  CHECK(c.vertices > 130);
  CHECK(c.texels > 100);
  // Both models: 64 clusters of 8 terms (the export's defaults) for more points than clusters; the
  // texels' weights float16. Measured 2.3e-8 and 6.2e-4 (the per-vertex weights of terms 1 and 2
  // swapped in the writer: 0.10).
  CHECK(c.vertex_error < 1e-4);
  CHECK(c.texel_error < 0.005);
  std::printf("mixed engine glTF: %zu vertices rel_rms %.2e, %zu texels rel_rms %.2e\n", c.vertices, c.vertex_error, c.texels, c.texel_error);
  // The source scene kept: its nodes with their names, its materials (none here).
  const Glb g = parse_glb(dir + "/m.glb");
  const json source = json::parse(read_file(dir + "/room.gltf"));
  REQUIRE(g.doc["nodes"].size() == source["nodes"].size());
  for (std::size_t n = 0; n < source["nodes"].size(); ++n) CHECK(g.doc["nodes"][n]["name"] == source["nodes"][n]["name"]);
  CHECK(g.doc.value("materials", json()) == source.value("materials", json()));
  // Deterministic: the same bytes for 3 threads.
  REQUIRE(test::run_prt(bake_command(dir + "/room.gltf", dir + "/t3", "--threads 3")).exit_code == 0);
  CHECK(read_file(dir + "/t3.glb") == read_file(dir + "/m.glb"));
  // prt's readers take one model per file: one line naming the primitive, exit 1, no output.
  const test::RunResult shade = test::run_prt("shade " + dir + "/m.glb " + dir + "/m.glb --lightmap --light " + kLight + " -o " + dir + "/s.exr");
  CHECK(test::fails_in_one_line(shade, dir + "/m.glb: PRT_transfer: mesh 1 primitive 0 uses model 1"));
  CHECK(!std::filesystem::exists(dir + "/s.exr"));
}

TEST_CASE("Mixed engine glTF with generated UVs: written from ROOM.mesh.glb, each primitive of one kind", "[pipeline][gltf][cli][mixed]") {
  const std::string dir = test::fresh_temp_dir("engine_gltf_mixed_uv");
  write_room_with_ball(dir + "/room.gltf");
  const test::RunResult r = test::run_prt(bake_command(dir + "/room.gltf", dir + "/g", "--uv generate"));
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  REQUIRE(std::filesystem::exists(dir + "/g.mesh.glb"));
  const MixedCheck c = check_mixed(dir + "/g.glb", dir + "/g.prt", dir + "/g.vertices.prt");
  CHECK(c.texel_primitives == 1);   // one material: one primitive per kind
  CHECK(c.vertex_primitives == 1);
  CHECK(c.vertex_error < 1e-4);
  CHECK(c.texel_error < 0.005);
  std::printf("mixed engine glTF, generated UVs: %zu vertices rel_rms %.2e, %zu texels rel_rms %.2e\n", c.vertices, c.vertex_error, c.texels,
              c.texel_error);
  const Glb g = parse_glb(dir + "/g.glb");
  for (const json& p : g.doc["meshes"][0]["primitives"])
    if (p["extensions"]["PRT_transfer"]["model"] == 0) CHECK(p["extensions"]["PRT_transfer"]["texCoord"] == 1);
}

TEST_CASE("Mixed engine glTF: bad input leaves none of the outputs", "[pipeline][gltf][cli][mixed]") {
  const std::string dir = test::fresh_temp_dir("engine_gltf_mixed_bad");
  std::vector<test::NamedPart> parts;
  test::write_gltf_parts(dir + "/room.gltf", test::room_with_box(true, parts), parts);
  // The glTF output in a folder that does not exist: refused before the bake, nothing written.
  const test::RunResult missing = test::run_prt("bake " + dir + "/room.gltf --lightmap 16 --texel-parts Floor -q -o " + dir +
                                                "/m.prt --gltf " + dir + "/none/m.glb");
  CHECK(test::fails_in_one_line(missing, dir + "/none/m.glb"));
  // The glTF output the same file as the pair's per-vertex file: refused, nothing written.
  const test::RunResult same = test::run_prt("bake " + dir + "/room.gltf --lightmap 16 --texel-parts Floor -q -o " + dir +
                                             "/m.prt --gltf " + dir + "/m.vertices.prt");
  CHECK(same.exit_code == 1);
  for (const char* name : {"m.prt", "m.vertices.prt", "none"}) CHECK(!std::filesystem::exists(dir + "/" + name));
  // Glossy transfer has no glTF form (texel bakes refuse glossy kinds): one line.
  const test::RunResult glossy = test::run_prt("bake " + dir + "/room.gltf --lightmap 16 --texel-parts Floor --transfer glossy-shadowed -q -o " +
                                               dir + "/m.prt --gltf " + dir + "/m.glb");
  CHECK(glossy.exit_code == 1);
  CHECK(!std::filesystem::exists(dir + "/m.glb"));
}
