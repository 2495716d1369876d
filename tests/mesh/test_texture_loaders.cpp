// Base colour textures through the loaders: glTF baseColorTexture from an external file, a buffer view
// and a data: URI (sampler, texCoord, KHR_texture_transform's texCoord override), OBJ map_Kd x Kd with
// -s / -o, images that cannot be decoded (a note, the factor alone), and a real third-party asset
// (BoxTextured, tests/data/README.md). PNGs are written with prt_image's encoder; the expected values
// come from the colours written, sRGB-decoded here by the IEC 61966-2-1 formula.
#include <cmath>
#include <cstring>
#include <filesystem>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "image/image.h"
#include "mesh/mesh.h"
#include "mesh/texture.h"
#include "mesh_test_util.h"

using namespace prt::mesh;
using namespace prt::mesh::test;
using nlohmann::json;

namespace {

// 8-bit codes of the two checker colours, and their linear values.
const glm::ivec3 kCodeA(255, 64, 128), kCodeB(0, 200, 32);

double srgb_decode(int code) {
  const double c = code / 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}
glm::vec3 linear(glm::ivec3 code) {
  return glm::vec3(float(srgb_decode(code.x)), float(srgb_decode(code.y)), float(srgb_decode(code.z)));
}

// An 8 x 8 PNG of 4 x 4-texel squares, a 2 x 2 checker: kCodeA top-left and bottom-right, else kCodeB.
std::string checker_png(const std::string& name) {
  prt::image::Image image(8, 8, 3);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x)
      for (int c = 0; c < 3; ++c) image.at(x, y, c) = float(((x / 4 + y / 4) % 2 == 0 ? kCodeA : kCodeB)[c]) / 255.0f;
  const std::string path = temp_path(name);
  prt::image::write(path, image);
  return path;
}

template <class T>
std::string pack(const std::vector<T>& values) {
  std::string out;
  for (T v : values) put(out, v);
  return out;
}

// The unit quad (z = 0, normal +z) as a .gltf with an external .bin: TEXCOORD_0 = (9, 9) everywhere (a
// decoy), TEXCOORD_1 = (x, y); baseColorTexture with texCoord 0 overridden to 1 by KHR_texture_transform
// (identity otherwise), NEAREST, and `image` as the image object. `png` is appended to the buffer.
std::string quad_gltf(const std::string& name, const json& image, const std::string& png = "") {
  std::string bin = pack<float>({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0});
  bin += pack<float>({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1});
  bin += pack<float>({9, 9, 9, 9, 9, 9, 9, 9});
  bin += pack<float>({0, 0, 1, 0, 1, 1, 0, 1});
  bin += pack<std::uint16_t>({0, 1, 2, 0, 2, 3});
  bin += png;
  write_temp(name + ".bin", bin);
  const json views = {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 48}},   {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 48}},
                      {{"buffer", 0}, {"byteOffset", 96}, {"byteLength", 32}},  {{"buffer", 0}, {"byteOffset", 128}, {"byteLength", 32}},
                      {{"buffer", 0}, {"byteOffset", 160}, {"byteLength", 12}}, {{"buffer", 0}, {"byteOffset", 172}, {"byteLength", png.size()}}};
  const json accessors = {{{"bufferView", 0}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}, {"min", {0, 0, 0}}, {"max", {1, 1, 0}}},
                          {{"bufferView", 1}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}},
                          {{"bufferView", 2}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}},
                          {{"bufferView", 3}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}},
                          {{"bufferView", 4}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}}};
  const json texture_info = {{"index", 0}, {"texCoord", 0}, {"extensions", {{"KHR_texture_transform", {{"texCoord", 1}}}}}};
  const json doc = {
      {"asset", {{"version", "2.0"}}},
      {"extensionsUsed", {"KHR_texture_transform"}},
      {"buffers", {{{"uri", name + ".bin"}, {"byteLength", bin.size()}}}},
      {"bufferViews", views},
      {"accessors", accessors},
      {"images", {image}},
      {"samplers", {{{"magFilter", 9728}, {"wrapS", 33071}, {"wrapT", 33071}}}},
      {"textures", {{{"sampler", 0}, {"source", 0}}}},
      {"materials", {{{"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 1.0, 1.0, 1.0}}, {"baseColorTexture", texture_info}}}}}},
      {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}, {"TEXCOORD_1", 3}}}, {"indices", 4}, {"material", 0}}}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"scenes", {{{"nodes", {0}}}}}};
  return write_temp(name + ".gltf", doc.dump());
}

void check_close(const glm::vec3& got, const glm::vec3& want, double tolerance) {
  for (int c = 0; c < 3; ++c) CHECK(double(got[c]) == Approx(double(want[c])).margin(tolerance));
}

// The checker quad's per-vertex albedo, within 1% of the exact footprint averages (test_texture.cpp
// derives them): (5 A + 3 B) / 8 at (0,0) and (1,1), (A + 3 B) / 4 at (1,0) and (0,1); factor (0.5, 1, 1).
void check_checker_quad(const Mesh& mesh) {
  const glm::vec3 factor(0.5f, 1.0f, 1.0f), a = linear(kCodeA), b = linear(kCodeB);
  const glm::vec3 corner = factor * (5.0f * a + 3.0f * b) / 8.0f, side = factor * (a + 3.0f * b) / 4.0f;
  REQUIRE(mesh.albedo.size() == 4);
  for (int c = 0; c < 3; ++c) {
    CHECK(mesh.albedo[0][c] == Approx(corner[c]).epsilon(0.01));
    CHECK(mesh.albedo[2][c] == Approx(corner[c]).epsilon(0.01));
    CHECK(mesh.albedo[1][c] == Approx(side[c]).epsilon(0.01));
    CHECK(mesh.albedo[3][c] == Approx(side[c]).epsilon(0.01));
  }
  // Texel (0, 0) is A: the base colour near the quad's (0, 0) corner, triangle 0.
  check_close(base_color(mesh, 0, 0.05, 0.05), factor * a, 1e-6);
}

}  // namespace

TEST_CASE("glTF baseColorTexture from a file, a buffer view and a data: URI", "[mesh][texture][gltf]") {
  const std::string png = checker_png("checker.png");
  const std::string png_bytes = read_bytes(png);
  const std::string external = quad_gltf("external", {{"uri", "checker.png"}});
  const std::string view = quad_gltf("view", {{"bufferView", 5}, {"mimeType", "image/png"}}, png_bytes);
  const std::string data = quad_gltf("data", {{"uri", "data:image/png;base64," + base64(png_bytes)}});
  // The memory budget is checked from the header: 8 x 8 x 3 floats are 768 bytes.
  CHECK(error_of([&] { prt::image::decode_rgb(png_bytes, "png", "budget", 767.0); }) ==
        "budget: image of 8x8 pixels needs more memory than is left for it");
  CHECK(prt::image::decode_rgb(png_bytes, "png", "budget", 768.0).width == 8);
  for (const std::string& path : {external, view, data}) {
    INFO(path);
    LoadReport report;
    const Mesh mesh = load_mesh(path, &report, true);
    CHECK(report.notes.empty());
    CHECK(mesh.albedo_source == AlbedoSource::texture);
    REQUIRE(mesh.textures.size() == 1);
    CHECK(mesh.textures[0].width == 8);
    CHECK(mesh.materials[0].base_color.texcoord == 1);
    CHECK(mesh.materials[0].base_color.filter == Filter::nearest);
    CHECK(mesh.materials[0].base_color.wrap_s == Wrap::clamp_to_edge);
    check_checker_quad(mesh);
  }
}

TEST_CASE("glTF images that cannot be decoded are a note - the factor alone is used", "[mesh][texture][gltf]") {
  const std::string ktx2 = std::string("\xABKTX 20\xBB\r\n\x1A\n", 12) + std::string(64, '\0');
  const std::string corrupt = std::string("\x89PNG\r\n\x1A\n", 8) + std::string(40, 'x');
  for (const std::string& bytes : {ktx2, corrupt}) {
    const std::string path = quad_gltf("bad", {{"bufferView", 5}, {"mimeType", "image/png"}}, bytes);
    LoadReport report;
    const Mesh mesh = load_mesh(path, &report, true);
    for (const std::string& note : report.notes) INFO(note);
    REQUIRE(report.notes.size() == 1);
    INFO(report.notes[0]);
    CHECK(report.notes[0].rfind("material 0 baseColorTexture", 0) == std::string::npos);
    CHECK(report.notes[0].find("image 0 (embedded)") == 0);
    CHECK(report.notes[0].find("its materials use the base colour factor alone") != std::string::npos);
    CHECK(mesh.albedo_source == AlbedoSource::material);
    CHECK(mesh.albedo[1] == glm::vec3(0.5f, 1.0f, 1.0f));
  }
}

TEST_CASE("a glTF primitive without its texture's TEXCOORD set uses the factor alone, with a note", "[mesh][texture][gltf]") {
  checker_png("checker.png");
  const std::string text = read_bytes(quad_gltf("no_uv", {{"uri", "checker.png"}}));
  json doc = json::parse(text);
  doc["meshes"][0]["primitives"][0]["attributes"].erase("TEXCOORD_1");
  const std::string path = write_temp("no_uv.gltf", doc.dump());
  LoadReport report;
  const Mesh mesh = load_mesh(path, &report, true);
  REQUIRE(report.notes.size() == 1);
  CHECK(report.notes[0] == "mesh 0 primitive 0 has no TEXCOORD_1 for its base colour texture; its base colour factor alone is used");
  CHECK(mesh.albedo_source == AlbedoSource::material);
  check_close(base_color(mesh, 0, 0.2, 0.2), glm::vec3(0.5f, 1.0f, 1.0f), 0.0);
}

TEST_CASE("OBJ map_Kd x Kd with -s and -o", "[mesh][texture][obj]") {
  checker_png("obj_checker.png");
  // vt = (x, 1 - y) (OBJ's v up), so prt's v-down UV is (x, y) before the options. -s 0.5 0.5 -o 0.5 0:
  // in OBJ coordinates u' = 0.5 + 0.5 u, v' = 0.5 v: the quad shows the image's bottom-right quadrant
  // (u' in [0.5, 1], v_down' = 1 - v' in [0.5, 1]), all A.
  write_temp("tex.mtl", "newmtl lit\nKd 0.5 0.25 1\nmap_Kd -s 0.5 0.5 1 -o 0.5 0 0 obj_checker.png\n"
                        "newmtl gone\nKd 0.3 0.3 0.3\nmap_Kd missing.png\n");
  const std::string path = write_temp("tex.obj", "mtllib tex.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                                                 "vt 0 1\nvt 1 1\nvt 1 0\nvt 0 0\nvn 0 0 1\nusemtl lit\nf 1/1/1 2/2/1 3/3/1\n"
                                                 "usemtl gone\nf 1/1/1 3/3/1 4/4/1\n");
  LoadReport report;
  const Mesh mesh = load_mesh(path, &report, true);
  for (const std::string& note : report.notes) UNSCOPED_INFO(note);
  CHECK(mesh.albedo_source == AlbedoSource::texture);
  REQUIRE(report.notes.size() == 1);
  CHECK(report.notes[0].find("material gone map_Kd") == 0);
  const glm::vec3 a = linear(kCodeA);
  // Points whose bilinear lookups stay among the quadrant's texel centres (u', v' in [4.5/8, 7.5/8]).
  for (double b1 : {0.1, 0.3, 0.5}) check_close(base_color(mesh, 0, b1, 0.3), glm::vec3(0.5f, 0.25f, 1.0f) * a, 1e-6);
  check_close(base_color(mesh, 1, 0.3, 0.3), glm::vec3(0.3f), 1e-6);
  // The images are inputs of the OBJ as much as its MTL file (outputs may not overwrite them).
  CHECK(referenced_files(path) == std::vector<std::string>{temp_path("tex.mtl"), temp_path("obj_checker.png"), temp_path("missing.png")});
}

TEST_CASE("OBJ map_Kd written on Windows (backslash folders) finds its file", "[mesh][texture][obj]") {
  // assimp-testmodels' spider.mtl writes "map_Kd .\\wal67ar_small.jpg"; here a folder too.
  std::filesystem::create_directories(temp_path("win_textures"));
  checker_png("win_textures/checker.png");
  write_temp("win.mtl", "newmtl lit\nKd 1 1 1\nmap_Kd .\\win_textures\\checker.png\n");
  const std::string path = write_temp("win.obj", "mtllib win.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\n"
                                                 "vt 0 1\nvt 1 1\nvt 1 0\nvn 0 0 1\nusemtl lit\nf 1/1/1 2/2/1 3/3/1\n");
  LoadReport report;
  const Mesh mesh = load_mesh(path, &report, true);
  for (const std::string& note : report.notes) UNSCOPED_INFO(note);
  CHECK(report.notes.empty());
  CHECK(mesh.albedo_source == AlbedoSource::texture);
  CHECK(referenced_files(path) == std::vector<std::string>{temp_path("win.mtl"), temp_path("./win_textures/checker.png")});
}

TEST_CASE("BoxTextured (glTF sample model, tests/data/BoxTextured) shows its texture", "[mesh][texture][gltf][asset]") {
  const std::string folder = std::string(PRT_SOURCE_DIR) + "/tests/data/BoxTextured/";
  // The PNG read from its file by prt_image, and bilinear lookups written out here (texel centres at
  // (x + 1/2) / width), at triangle centroids, whose UVs lie inside the image in this asset.
  const prt::image::Image png = prt::image::read_rgb(folder + "CesiumLogoFlat.png");
  auto bilinear = [&](glm::vec2 uv) {
    const double x = uv.x * png.width - 0.5, y = uv.y * png.height - 0.5;
    const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
    const double fx = x - x0, fy = y - y0;
    glm::dvec3 sum(0.0);
    for (int dy = 0; dy < 2; ++dy)
      for (int dx = 0; dx < 2; ++dx) {
        const int px = std::min(std::max(x0 + dx, 0), png.width - 1), py = std::min(std::max(y0 + dy, 0), png.height - 1);
        const double w = (dx ? fx : 1 - fx) * (dy ? fy : 1 - fy);
        for (int c = 0; c < 3; ++c) sum[c] += w * png.at(px, py, c);
      }
    return glm::vec3(sum);
  };
  // u runs over [0, 6] on the box's sides; the .glb's sampler repeats it, the .gltf's mirrors it
  // (wrapS MIRRORED_REPEAT): the centroid's u folded into [0, 1] by hand here for each.
  for (const bool mirrored : {false, true}) {
    const std::string file = mirrored ? "BoxTextured.gltf" : "BoxTextured.glb";
    INFO(file);
    LoadReport report;
    const Mesh mesh = load_mesh(folder + file, &report, true);
    CHECK(report.notes.empty());
    CHECK(mesh.albedo_source == AlbedoSource::texture);
    REQUIRE(mesh.textures.size() == 1);
    CHECK(mesh.textures[0].width == png.width);
    CHECK(mesh.textures[0].height == png.height);
    REQUIRE(mesh.triangle_count() == 12);
    for (std::uint32_t t = 0; t < mesh.triangle_count(); ++t) {
      glm::vec2 uv = (mesh.base_color_uv[3 * t] + mesh.base_color_uv[3 * t + 1] + mesh.base_color_uv[3 * t + 2]) / 3.0f;
      const float whole = std::floor(uv.x);
      uv.x = mirrored && int(whole) % 2 == 1 ? 1.0f - (uv.x - whole) : uv.x - whole;
      REQUIRE((uv.x > 0.01f && uv.x < 0.99f && uv.y > 0.01f && uv.y < 0.99f));
      check_close(base_color(mesh, t, 1.0 / 3.0, 1.0 / 3.0), bilinear(uv), 1e-5);
    }
    // Per-vertex albedo comes from the texture, not the factor 1 (white) of the untextured box.
    float lo = 1.0f, hi = 0.0f;
    for (const glm::vec3& a : mesh.albedo) lo = std::min(lo, a.g), hi = std::max(hi, a.g);
    CHECK(hi < 0.95f);
    CHECK(hi - lo > 0.05f);
  }
}

TEST_CASE("8-bit sRGB images are held as their codes and read back bit for bit as decoded", "[mesh][texture][obj]") {
  // A 16 x 16 PNG holding every code in each channel, in three different orders.
  auto code = [](int i, int c) { return c == 0 ? i : c == 1 ? 255 - i : (7 * i + 3) % 256; };
  prt::image::Image image(16, 16, 3);
  for (int i = 0; i < 256; ++i)
    for (int c = 0; c < 3; ++c) image.at(i % 16, i / 16, c) = float(code(i, c)) / 255.0f;
  const std::string png = temp_path("codes.png");
  prt::image::write(png, image);
  write_temp("codes.mtl", "newmtl m\nKd 1 1 1\nmap_Kd codes.png\n");
  const Mesh mesh = load_mesh(write_temp("codes.obj", "mtllib codes.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\n"
                                                      "vt 0 1\nvn 0 0 1\nusemtl m\nf 1/1/1 2/2/1 3/3/1\n"),
                              nullptr, true);
  REQUIRE(mesh.textures.size() == 1);
  const Texture& packed = mesh.textures[0];
  CHECK(packed.rgb.empty());
  REQUIRE(packed.codes.size() == 768);
  for (int i = 0; i < 256; ++i)
    for (int c = 0; c < 3; ++c) CHECK(int(packed.codes[std::size_t(3 * i + c)]) == code(i, c));
  // The truth: the same file decoded to floats by prt_image, and the float-held texture's lookups.
  const prt::image::Image decoded = prt::image::read_rgb(png);
  const std::vector<float> rgb = texture_rgb(packed);
  REQUIRE(rgb.size() == decoded.pixels.size());
  CHECK(std::memcmp(rgb.data(), decoded.pixels.data(), rgb.size() * sizeof(float)) == 0);
  Texture floats;
  floats.width = floats.height = 16;
  floats.rgb = decoded.pixels;
  for (const Filter filter : {Filter::linear, Filter::nearest})
    for (const Wrap wrap : {Wrap::repeat, Wrap::clamp_to_edge, Wrap::mirrored_repeat}) {
      TextureRef ref;
      ref.filter = filter;
      ref.wrap_s = ref.wrap_t = wrap;
      for (int k = 0; k < 400; ++k) {
        const glm::vec2 uv(-1.3f + 0.0113f * float(k), 2.1f - 0.0097f * float(k));
        const glm::vec3 want = sample_texture(floats, ref, uv), got = sample_texture(packed, ref, uv);
        INFO("filter " << int(filter) << " wrap " << int(wrap) << " uv " << uv.x << ", " << uv.y);
        CHECK(std::memcmp(&got, &want, sizeof(got)) == 0);
      }
    }
  // Values that are no code's decode (another float, -0) keep a texture in floats.
  for (const float odd : {0.5f, -0.0f}) {
    Texture t = floats;
    t.rgb[5] = odd;
    pack_srgb8(&t);
    CHECK(t.codes.empty());
    CHECK(t.rgb.size() == 768);
  }
}
