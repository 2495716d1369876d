#include "mesh/obj_materials.h"

#include <charconv>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>
#include <string_view>

#include "core/atomic_file.h"
#include "core/error.h"

namespace prt::mesh::detail {

namespace {

// map_Kd's -s and -o, which act on OBJ's v-up coordinates (u' = o + s u), as a transform of prt's
// v-down ones: v_down' = 1 - (o_v + s_v (1 - v_down)) = (1 - o_v - s_v) + s_v v_down.
TextureTransform mtl_transform(const tinyobj::texture_option_t& option) {
  TextureTransform t;
  t.scale = glm::vec2(float(option.scale[0]), float(option.scale[1]));
  t.offset = glm::vec2(float(option.origin_offset[0]), 1.0f - float(option.origin_offset[1]) - float(option.scale[1]));
  return t;
}

std::string_view trimmed(std::string_view s) {
  const std::size_t first = s.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  return s.substr(first, s.find_last_not_of(" \t\r") - first + 1);
}

// The value of a Pr or Pm line (`rest`: the line after its tag): one finite number in [0, 1], else
// prt::Error naming the file, the line and the material.
float pbr_value(const std::string& file, std::size_t line_number, const std::string& material, std::string_view tag,
                std::string_view rest) {
  const std::string_view token = trimmed(rest);
  double value = 0.0;
  const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (token.empty() || ec != std::errc() || ptr != token.data() + token.size() || !std::isfinite(value) ||
      value < 0.0 || value > 1.0)
    fail_file(file, "line " + std::to_string(line_number) + ": material " + material + ": " + std::string(tag) + " \"" +
                        std::string(token.substr(0, 30)) + "\" is not one number in [0, 1]");
  return float(value);
}

// The file an MTL texture name refers to, against the OBJ's folder: the name as written, or, when no
// such file exists and the name holds backslashes (MTL files written on Windows: "map_Kd .\\wood.jpg"),
// the name with them read as folder separators.
std::string mtl_texture_path(const std::string& folder, const std::string& name) {
  const std::string literal = folder + name;
  if (name.find('\\') == std::string::npos || std::filesystem::exists(literal)) return literal;
  std::string slashed = name;
  std::replace(slashed.begin(), slashed.end(), '\\', '/');
  return folder + slashed;
}

}  // namespace

void scan_mtl_pbr(const std::string& file, const std::string& text, std::map<std::string, MtlPbr>* keys) {
  std::istringstream lines(text);
  std::size_t line_number = 0;
  MtlPbr* current = nullptr;  // the material being defined, or null (none yet, or a repeated name)
  std::string name;
  for (std::string line; std::getline(lines, line);) {
    ++line_number;
    const std::string_view body = trimmed(line);
    const std::size_t tag_end = std::min(body.find_first_of(" \t"), body.size());
    const std::string_view tag = body.substr(0, tag_end), rest = body.substr(tag_end);
    if (tag == "newmtl") {
      name = std::string(trimmed(rest));
      const auto [it, fresh] = keys->emplace(name, MtlPbr{});
      current = fresh ? &it->second : nullptr;
    } else if (current == nullptr) {
      continue;
    } else if (tag == "Pr") {
      current->roughness = pbr_value(file, line_number, name, tag, rest);
    } else if (tag == "Pm") {
      current->metallic = pbr_value(file, line_number, name, tag, rest);
    } else if (tag == "map_Pr" || tag == "map_Pm") {
      current->textured = true;
    }
  }
}

std::vector<std::string> mtl_texture_files(const std::string& mtl_path, const std::string& folder) {
  std::vector<std::string> files;
  std::string text;
  try {
    text = read_file(mtl_path);
  } catch (const Error&) {
    return files;
  }
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    std::istringstream words(line);
    std::string tag, word, last;
    if (!(words >> tag) || tag != "map_Kd") continue;
    while (words >> word) last = word;
    if (!last.empty()) files.push_back(mtl_texture_path(folder, last));
  }
  return files;
}

void obj_material_list(const std::string& folder, const std::vector<tinyobj::material_t>& mtl,
                       const std::map<std::string, MtlPbr>& pbr, RawMesh* raw) {
  std::map<std::string, int> decoded;  // map_Kd file -> texture index, or -1 if it failed
  std::uint64_t held_bytes = 0;
  for (const tinyobj::material_t& m : mtl) {
    Material material;
    material.name = m.name;
    material.base_color_factor = glm::vec3(float(m.diffuse[0]), float(m.diffuse[1]), float(m.diffuse[2]));
    const auto keys = pbr.find(std::string(trimmed(m.name)));
    if (keys != pbr.end()) {
      material.roughness_factor = keys->second.roughness.value_or(material.roughness_factor);
      material.metallic_factor = keys->second.metallic.value_or(material.metallic_factor);
      material.metallic_roughness_textured = keys->second.textured;
    }
    if (!m.diffuse_texname.empty()) {
      const std::string file = mtl_texture_path(folder, m.diffuse_texname);
      auto [it, fresh] = decoded.emplace(file, -1);
      if (fresh) {
        Texture texture;
        std::string problem;
        try {
          if (decode_texture(read_file(file), file, file, &held_bytes, &texture, &problem)) {
            it->second = int(raw->textures.size());
            raw->textures.push_back(std::move(texture));
          }
        } catch (const Error& e) {
          problem = e.what();
        }
        if (it->second < 0)
          raw->notes_only.notes.push_back("material " + m.name + " map_Kd " + problem + "; its Kd alone is used");
      }
      material.base_color.image = it->second;
      material.base_color.transform = mtl_transform(m.diffuse_texopt);
      if (m.diffuse_texopt.clamp) material.base_color.wrap_s = material.base_color.wrap_t = Wrap::clamp_to_edge;
    }
    raw->materials.push_back(std::move(material));
  }
  raw->materials.push_back(Material{"(none)", glm::vec3(kDefaultKd), TextureRef{}});
}

}  // namespace prt::mesh::detail
