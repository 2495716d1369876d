#include "mesh/obj_materials.h"

#include <map>
#include <sstream>

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

}  // namespace

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
    if (!last.empty()) files.push_back(folder + last);
  }
  return files;
}

void obj_material_list(const std::string& folder, const std::vector<tinyobj::material_t>& mtl, RawMesh* raw) {
  std::map<std::string, int> decoded;  // map_Kd file -> texture index, or -1 if it failed
  std::uint64_t held_bytes = 0;
  for (const tinyobj::material_t& m : mtl) {
    Material material;
    material.name = m.name;
    material.base_color_factor = glm::vec3(float(m.diffuse[0]), float(m.diffuse[1]), float(m.diffuse[2]));
    if (!m.diffuse_texname.empty()) {
      const std::string file = folder + m.diffuse_texname;
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
