// glTF export: the scene re-written as one .glb with EXT_lights_image_based (see exporters.h and
// probes/gltf/README.md). The scene's buffers (GLB BIN chunk, external .bin files, data URIs) are merged
// into one BIN chunk and its images embedded as buffer views, so the .glb stands alone.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>

#include <glm/common.hpp>

#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/json_depth.h"
#include "core/little_endian.h"
#include "core/text.h"
#include "image/image.h"
#include "light/environment.h"
#include "mesh/mesh.h"
#include "mesh/writers.h"
#include "probes/engine_sh.h"
#include "probes/exporters.h"
#include "sh/basis.h"

namespace prt::probes {

namespace {

using Json = nlohmann::json;

using le::get_u32;
using le::put_u32;

std::string base64_decode(const std::string& in, const std::string& name) {
  auto value = [](char c) -> int {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+' || c == '-') return 62;
    if (c == '/' || c == '_') return 63;
    return -1;
  };
  std::string out;
  std::uint32_t bits = 0;
  int count = 0;
  for (char c : in) {
    if (c == '=' || c == '\n' || c == '\r') continue;
    const int v = value(c);
    if (v < 0) fail_file(name, "invalid base64 data URI");
    bits = (bits << 6) | static_cast<std::uint32_t>(v);
    count += 6;
    if (count >= 8) {
      count -= 8;
      out.push_back(static_cast<char>((bits >> count) & 0xFF));
    }
  }
  return out;
}

// The bytes a URI names: a base64 data URI or a file relative to the scene's folder.
std::string uri_bytes(const std::string& uri, const std::string& base_dir, const std::string& name, std::string* mime) {
  if (uri.rfind("data:", 0) == 0) {
    const std::size_t comma = uri.find(',');
    if (comma == std::string::npos || uri.find(";base64") == std::string::npos || uri.find(";base64") > comma)
      fail_file(name, "only base64 data URIs are supported");
    if (mime) *mime = uri.substr(5, uri.find(';') - 5);
    return base64_decode(uri.substr(comma + 1), name);
  }
  std::string path = uri;
  for (std::size_t at; (at = path.find("%20")) != std::string::npos;) path.replace(at, 3, " ");
  if (mime) {
    const std::string ext = to_lower(std::filesystem::path(path).extension().string());
    *mime = (ext == ".jpg" || ext == ".jpeg") ? "image/jpeg" : (ext == ".ktx2" ? "image/ktx2" : "image/png");
  }
  return read_file((std::filesystem::path(base_dir) / path).string());
}

struct GltfDocument {
  Json json;
  std::string bin;  // the one merged buffer
};

GltfDocument parse_glb(const std::string& bytes, const std::string& name) {
  if (bytes.size() < 20 || bytes.compare(0, 4, "glTF") != 0 || get_u32(bytes, 4) != 2)
    fail_file(name, "not a glTF 2.0 binary (.glb)");
  GltfDocument doc;
  std::size_t at = 12;
  bool have_json = false;
  while (at + 8 <= bytes.size()) {
    const std::uint32_t length = get_u32(bytes, at), type = get_u32(bytes, at + 4);
    if (at + 8 + static_cast<std::size_t>(length) > bytes.size()) fail_file(name, "truncated GLB chunk");
    const std::string chunk = bytes.substr(at + 8, length);
    if (type == 0x4E4F534Au) {
      check_json_depth(chunk, name);
      doc.json = Json::parse(chunk, nullptr, false);
      have_json = true;
    } else if (type == 0x004E4942u && doc.bin.empty()) {
      doc.bin = chunk;
    }
    at += 8 + length;
  }
  if (!have_json || doc.json.is_discarded() || !doc.json.is_object()) fail_file(name, "GLB has no valid JSON chunk");
  return doc;
}

// Appends `bytes` to the merged buffer as a new buffer view; returns its index.
std::size_t add_buffer_view(GltfDocument& doc, const std::string& bytes) {
  while (doc.bin.size() % 8 != 0) doc.bin.push_back('\0');
  doc.json["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", doc.bin.size()}, {"byteLength", bytes.size()}});
  doc.bin += bytes;
  return doc.json["bufferViews"].size() - 1;
}

// Loads any scene into one JSON + one merged buffer with every image embedded as a buffer view.
GltfDocument load_scene(const std::string& path, const std::string& out_path) {
  const std::string ext = to_lower(std::filesystem::path(path).extension().string());
  const std::string base_dir = std::filesystem::path(path).parent_path().string();
  std::vector<std::string> buffers;
  GltfDocument doc;
  if (ext == ".glb") {
    doc = parse_glb(read_file(path), path);
  } else if (ext == ".gltf") {
    const std::string text = read_file(path);
    check_json_depth(text, path);
    doc.json = Json::parse(text, nullptr, false);
    if (doc.json.is_discarded() || !doc.json.is_object()) fail_file(path, "not a glTF JSON document");
  } else {
    // OBJ, PLY: the mesh as prt loads it, through the GLB writer.
    const mesh::Mesh mesh = mesh::load_mesh(path, nullptr, true);
    AtomicFile staging(out_path + ".scene.glb");
    mesh::write_glb(staging.temp_path(), mesh);
    doc = parse_glb(read_file(staging.temp_path()), path);
    std::filesystem::remove(staging.temp_path());
  }
  // Buffers: index 0 without uri is the GLB BIN chunk; the rest come from their URIs.
  if (doc.json.contains("buffers")) {
    for (std::size_t b = 0; b < doc.json["buffers"].size(); ++b) {
      const Json& buffer = doc.json["buffers"][b];
      if (buffer.contains("uri")) buffers.push_back(uri_bytes(buffer["uri"].get<std::string>(), base_dir, path, nullptr));
      else if (b == 0) buffers.push_back(doc.bin);
      else fail_file(path, "buffer " + std::to_string(b) + " has no uri");
    }
  }
  std::vector<std::size_t> base;
  std::string merged;
  for (const std::string& b : buffers) {
    while (merged.size() % 8 != 0) merged.push_back('\0');
    base.push_back(merged.size());
    merged += b;
  }
  if (doc.json.contains("bufferViews"))
    for (Json& view : doc.json["bufferViews"]) {
      const std::size_t b = view.value("buffer", 0u);
      if (b >= base.size()) fail_file(path, "a bufferView names a missing buffer");
      view["buffer"] = 0;
      view["byteOffset"] = view.value("byteOffset", std::size_t{0}) + base[b];
    }
  doc.bin = merged;
  if (!doc.json.contains("bufferViews")) doc.json["bufferViews"] = Json::array();
  if (doc.json.contains("images"))
    for (Json& image : doc.json["images"]) {
      if (!image.contains("uri")) continue;
      std::string mime;
      const std::string bytes = uri_bytes(image["uri"].get<std::string>(), base_dir, path, &mime);
      image.erase("uri");
      image["bufferView"] = add_buffer_view(doc, bytes);
      image["mimeType"] = mime;
    }
  return doc;
}

// Babylon.js's RGBD encoding (Shaders/ShadersInclude/helperFunctions.fx toRGBD, rgbdMaxRange 255):
// D = clamp(floor(max(255 / max(r,g,b), 1)) / 255, 0, 1), rgb' = clamp((rgb D)^(1/2.2), 0, 1), alpha = D.
void rgbd_encode(const glm::dvec3& radiance, float* out) {
  const double max_rgb = std::max({radiance.x, radiance.y, radiance.z, 1e-6});
  const double d = std::clamp(std::floor(std::max(255.0 / max_rgb, 1.0)) / 255.0, 0.0, 1.0);
  for (int k = 0; k < 3; ++k) out[k] = static_cast<float>(std::clamp(std::pow(std::max(radiance[k] * d, 0.0), 1.0 / 2.2), 0.0, 1.0));
  out[3] = static_cast<float>(d);
}

std::string png_bytes(const image::Image& rgbd, const std::string& out_path) {
  AtomicFile staging(out_path + ".face.png");
  image::write_file_at(staging.temp_path(), rgbd, staging.path());
  std::string bytes = read_file(staging.temp_path());
  std::filesystem::remove(staging.temp_path());
  return bytes;
}

// Babylon.js's frame for the image-based light: its glTF loader mirrors the scene (x -> -x, the
// "__root__" node) into its left-handed world but uses the light as stored, so the light is written
// mirrored in x: a glTF direction d appears as (-d.x, d.y, d.z) in the cube and in the coefficients.
glm::dvec3 babylon_cube_to_gltf(const glm::dvec3& d) { return {-d.x, d.y, d.z}; }

// Radiance of the light in glTF direction d: the environment, or the sky probe's (clamped) SH.
glm::dvec3 sky_radiance(const ProbeSet& probes, const ExportOptions& options, const glm::dvec3& d) {
  if (options.environment) return options.environment->radiance(d);
  std::vector<double> basis(probes.sky.values.size());
  sh::eval(probes.sky.bands, d, basis.data());
  glm::dvec3 radiance(0.0);
  for (std::size_t i = 0; i < basis.size(); ++i) radiance += probes.sky.values[i] * basis[i];
  return glm::max(radiance, glm::dvec3(0.0));
}

using CubeLevel = std::array<image::Image, 6>;

// Mip 0 of the specular cube: each face in OpenGL cube orientation (conventions.md) of Babylon's frame,
// sampled at texel centres; rows stored bottom first (image row y is the face's row size-1-y), because
// Babylon uploads the images with UNPACK_FLIP_Y, as EXT_lights_image_based stores its faces.
CubeLevel specular_mip0(const ProbeSet& probes, const ExportOptions& options, int size) {
  CubeLevel level;
  for (int f = 0; f < 6; ++f) {
    level[f] = image::Image(size, size, 3);
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        const glm::dvec3 d = light::cube_direction(f, (x + 0.5) / size, (size - 1 - y + 0.5) / size);
        const glm::dvec3 radiance = sky_radiance(probes, options, babylon_cube_to_gltf(d));
        for (int c = 0; c < 3; ++c) level[f].at(x, y, c) = static_cast<float>(radiance[c]);
      }
  }
  return level;
}

// The 2x2 box average of every face (not a GGX prefilter; see the README).
CubeLevel half_level(const CubeLevel& above) {
  CubeLevel next;
  const int s = above[0].width / 2;
  for (int f = 0; f < 6; ++f) {
    next[f] = image::Image(s, s, 3);
    for (int y = 0; y < s; ++y)
      for (int x = 0; x < s; ++x)
        for (int c = 0; c < 3; ++c)
          next[f].at(x, y, c) = 0.25f * (above[f].at(2 * x, 2 * y, c) + above[f].at(2 * x + 1, 2 * y, c) +
                                         above[f].at(2 * x, 2 * y + 1, c) + above[f].at(2 * x + 1, 2 * y + 1, c));
  }
  return next;
}

// Embeds every level's six faces as RGBD PNG images; returns specularImages (image indices per level).
Json embed_specular_images(GltfDocument& doc, const std::vector<CubeLevel>& levels, const std::string& path) {
  if (!doc.json.contains("images")) doc.json["images"] = Json::array();
  Json specular = Json::array();
  for (std::size_t mip = 0; mip < levels.size(); ++mip) {
    Json faces = Json::array();
    for (int f = 0; f < 6; ++f) {
      const image::Image& face = levels[mip][f];
      image::Image rgbd(face.width, face.height, 4);
      for (int y = 0; y < rgbd.height; ++y)
        for (int x = 0; x < rgbd.width; ++x)
          rgbd_encode(glm::dvec3(face.at(x, y, 0), face.at(x, y, 1), face.at(x, y, 2)), &rgbd.at(x, y, 0));
      const std::size_t view = add_buffer_view(doc, png_bytes(rgbd, path));
      doc.json["images"].push_back({{"name", "prt specular mip " + std::to_string(mip) + " face " + std::to_string(f)},
                                    {"bufferView", view},
                                    {"mimeType", "image/png"}});
      faces.push_back(doc.json["images"].size() - 1);
    }
    specular.push_back(faces);
  }
  return specular;
}

// Adds the light to the root extension and references it from every scene.
void attach_light(Json& j, Json light) {
  if (!j.contains("extensions")) j["extensions"] = Json::object();
  j["extensions"]["EXT_lights_image_based"] = {{"lights", Json::array({std::move(light)})}};
  if (!j.contains("extensionsUsed")) j["extensionsUsed"] = Json::array();
  if (std::find(j["extensionsUsed"].begin(), j["extensionsUsed"].end(), "EXT_lights_image_based") == j["extensionsUsed"].end())
    j["extensionsUsed"].push_back("EXT_lights_image_based");
  if (!j.contains("scenes") || j["scenes"].empty()) j["scenes"] = Json::array({Json::object()});
  for (Json& scene : j["scenes"]) scene["extensions"]["EXT_lights_image_based"] = {{"light", 0}};
}

// The document as GLB bytes: JSON chunk padded with spaces, BIN chunk with zeros.
std::string glb_bytes(GltfDocument& doc) {
  while (doc.bin.size() % 4 != 0) doc.bin.push_back('\0');
  doc.json["buffers"] = Json::array({{{"byteLength", doc.bin.size()}}});
  if (!doc.json.contains("asset")) doc.json["asset"] = {{"version", "2.0"}};
  doc.json["asset"]["generator"] = "prt probes (EXT_lights_image_based)";
  std::string text = doc.json.dump();
  while (text.size() % 4 != 0) text.push_back(' ');
  std::string glb = "glTF";
  put_u32(glb, 2);
  put_u32(glb, static_cast<std::uint32_t>(12 + 8 + text.size() + 8 + doc.bin.size()));
  put_u32(glb, static_cast<std::uint32_t>(text.size()));
  put_u32(glb, 0x4E4F534Au);
  glb += text;
  put_u32(glb, static_cast<std::uint32_t>(doc.bin.size()));
  put_u32(glb, 0x004E4942u);
  glb += doc.bin;
  return glb;
}

void check_gltf_options(const std::string& path, const ExportOptions& options) {
  if (lower_extension(path) != ".glb")
    fail_file(path, "the gltf export writes a binary glTF: the output must end in .glb");
  const int size = options.specular_size;
  if (size < 1 || size > 1024 || (size & (size - 1)) != 0)
    fail_option("specular_size", ": expected a power of two in 1..1024, got " + std::to_string(size));
  if (options.scene_path.empty()) fail("gltf export: no scene file given");
}

}  // namespace

void write_gltf(const ProbeSet& probes, const std::string& path, const ExportOptions& options) {
  check_probe_set(probes, "glTF export");
  check_gltf_options(path, options);
  AtomicFile out(path);
  GltfDocument doc;
  try {
    doc = load_scene(options.scene_path, path);
  } catch (const Json::exception& e) {  // a key of the wrong type in the scene's JSON
    const std::string what = e.what();  // "[json.exception.type_error.302] type must be ..."
    fail_file(options.scene_path, "malformed glTF scene: " + what.substr(what.find(']') + 2));
  }

  std::vector<CubeLevel> levels{specular_mip0(probes, options, options.specular_size)};
  while (levels.back()[0].width > 1) levels.push_back(half_level(levels.back()));
  Json coefficients = Json::array();
  for (const glm::dvec3& v : gltf_irradiance_coefficients(probes.sky)) coefficients.push_back({v.x, v.y, v.z});
  attach_light(doc.json, {{"name", "prt sky probe"},
                          {"intensity", 1.0},
                          {"rotation", {0.0, 0.0, 0.0, 1.0}},
                          {"irradianceCoefficients", coefficients},
                          {"specularImageSize", options.specular_size},
                          {"specularImages", embed_specular_images(doc, levels, path)}});
  const std::string glb = glb_bytes(doc);
  out.stream().write(glb.data(), static_cast<std::streamsize>(glb.size()));
  out.commit();
}

}  // namespace prt::probes
