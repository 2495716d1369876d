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

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

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
    const std::string ext = lower(std::filesystem::path(path).extension().string());
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

// Loads any scene into one JSON + one merged buffer with every image embedded as a buffer view.
GltfDocument load_scene(const std::string& path, const std::string& out_path) {
  const std::string ext = lower(std::filesystem::path(path).extension().string());
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
    mesh::write_glb(staging.temp_path(), mesh, {});
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
      while (doc.bin.size() % 8 != 0) doc.bin.push_back('\0');
      doc.json["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", doc.bin.size()}, {"byteLength", bytes.size()}});
      doc.bin += bytes;
      image.erase("uri");
      image["bufferView"] = doc.json["bufferViews"].size() - 1;
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

}  // namespace

void write_gltf(const ProbeSet& probes, const std::string& path, const ExportOptions& options) {
  check_probe_set(probes, "glTF export");
  if (lower(std::filesystem::path(path).extension().string()) != ".glb")
    fail_file(path, "the gltf export writes a binary glTF: the output must end in .glb");
  const int size = options.specular_size;
  if (size < 1 || size > 1024 || (size & (size - 1)) != 0)
    fail("--specular-size: expected a power of two in 1..1024, got " + std::to_string(size));
  if (options.scene_path.empty()) fail("gltf export: no scene file given");
  AtomicFile out(path);
  GltfDocument doc;
  try {
    doc = load_scene(options.scene_path, path);
  } catch (const Json::exception& e) {  // a key of the wrong type in the scene's JSON
    const std::string what = e.what();  // "[json.exception.type_error.302] type must be ..."
    fail_file(options.scene_path, "malformed glTF scene: " + what.substr(what.find(']') + 2));
  }
  Json& j = doc.json;
  if (!j.contains("images")) j["images"] = Json::array();

  // Specular cube: mip 0 sampled at texel centres (environment, or the sky probe's SH), each further
  // mip the 2x2 box average of the one above, down to 1x1 (not a GGX prefilter; see the README).
  std::vector<std::array<image::Image, 6>> levels;
  std::array<image::Image, 6> level0;
  for (int f = 0; f < 6; ++f) {
    level0[f] = image::Image(size, size, 3);
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        const glm::dvec3 d = light::cube_direction(f, (x + 0.5) / size, (y + 0.5) / size);
        glm::dvec3 radiance(0.0);
        if (options.environment) {
          radiance = options.environment->radiance(d);
        } else {
          std::vector<double> basis(probes.sky.values.size());
          sh::eval(probes.sky.bands, d, basis.data());
          for (std::size_t i = 0; i < basis.size(); ++i) radiance += probes.sky.values[i] * basis[i];
          radiance = glm::max(radiance, glm::dvec3(0.0));
        }
        for (int c = 0; c < 3; ++c) level0[f].at(x, y, c) = static_cast<float>(radiance[c]);
      }
  }
  levels.push_back(level0);
  for (int s = size / 2; s >= 1; s /= 2) {
    std::array<image::Image, 6> next;
    for (int f = 0; f < 6; ++f) {
      next[f] = image::Image(s, s, 3);
      const image::Image& above = levels.back()[f];
      for (int y = 0; y < s; ++y)
        for (int x = 0; x < s; ++x)
          for (int c = 0; c < 3; ++c)
            next[f].at(x, y, c) = 0.25f * (above.at(2 * x, 2 * y, c) + above.at(2 * x + 1, 2 * y, c) +
                                           above.at(2 * x, 2 * y + 1, c) + above.at(2 * x + 1, 2 * y + 1, c));
    }
    levels.push_back(next);
  }
  Json specular = Json::array();
  for (const auto& level : levels) {
    Json faces = Json::array();
    for (int f = 0; f < 6; ++f) {
      image::Image rgbd(level[f].width, level[f].height, 4);
      for (int y = 0; y < rgbd.height; ++y)
        for (int x = 0; x < rgbd.width; ++x)
          rgbd_encode(glm::dvec3(level[f].at(x, y, 0), level[f].at(x, y, 1), level[f].at(x, y, 2)), &rgbd.at(x, y, 0));
      const std::string png = png_bytes(rgbd, path);
      while (doc.bin.size() % 8 != 0) doc.bin.push_back('\0');
      j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", doc.bin.size()}, {"byteLength", png.size()}});
      doc.bin += png;
      j["images"].push_back({{"name", "prt specular mip " + std::to_string(&level - levels.data()) + " face " + std::to_string(f)},
                             {"bufferView", j["bufferViews"].size() - 1},
                             {"mimeType", "image/png"}});
      faces.push_back(j["images"].size() - 1);
    }
    specular.push_back(faces);
  }

  Json coefficients = Json::array();
  for (const glm::dvec3& v : gltf_irradiance_coefficients(probes.sky)) coefficients.push_back({v.x, v.y, v.z});
  Json light = {{"name", "prt sky probe"},
                {"intensity", 1.0},
                {"rotation", {0.0, 0.0, 0.0, 1.0}},
                {"irradianceCoefficients", coefficients},
                {"specularImageSize", size},
                {"specularImages", specular}};
  if (!j.contains("extensions")) j["extensions"] = Json::object();
  j["extensions"]["EXT_lights_image_based"] = {{"lights", Json::array({light})}};
  if (!j.contains("extensionsUsed")) j["extensionsUsed"] = Json::array();
  if (std::find(j["extensionsUsed"].begin(), j["extensionsUsed"].end(), "EXT_lights_image_based") == j["extensionsUsed"].end())
    j["extensionsUsed"].push_back("EXT_lights_image_based");
  if (!j.contains("scenes") || j["scenes"].empty()) j["scenes"] = Json::array({Json::object()});
  for (Json& scene : j["scenes"]) scene["extensions"]["EXT_lights_image_based"] = {{"light", 0}};
  while (doc.bin.size() % 4 != 0) doc.bin.push_back('\0');
  j["buffers"] = Json::array({{{"byteLength", doc.bin.size()}}});
  if (!j.contains("asset")) j["asset"] = {{"version", "2.0"}};
  j["asset"]["generator"] = "prt probes (EXT_lights_image_based)";

  std::string text = j.dump();
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
  out.stream().write(glb.data(), static_cast<std::streamsize>(glb.size()));
  out.commit();
}

}  // namespace prt::probes
