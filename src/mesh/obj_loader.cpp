// Wavefront OBJ (+ MTL) loading through tinyobjloader, keeping the "v" lines' order.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iterator>
#include <limits>
#include <map>
#include <sstream>
#include <string_view>
#include <utility>

#include <glm/geometric.hpp>
#include <tiny_obj_loader.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/text.h"
#include "mesh/loaders.h"
#include "mesh/obj_corner_vertices.h"
#include "mesh/obj_materials.h"

namespace prt::mesh::detail {

namespace {

/// Accumulates, per vertex, the distinct values (material indices) its corners reference.
/// Pairs are collected, then sorted and deduplicated, so each distinct value counts once per vertex.
class DistinctPairs {
 public:
  void add(std::uint32_t position, int value) { pairs_.emplace_back(position, value); }
  /// Calls f(position, value) once per distinct pair, in position order.
  template <class F>
  void for_each(F f) {
    std::sort(pairs_.begin(), pairs_.end());
    pairs_.erase(std::unique(pairs_.begin(), pairs_.end()), pairs_.end());
    for (const auto& [position, value] : pairs_) f(position, value);
  }

 private:
  std::vector<std::pair<std::uint32_t, int>> pairs_;
};

/// tinyobjloader reads face indices into an int without an overflow check ("4294967297" wraps to
/// vertex 1): every integer on an "f" line must fit in 32 bits (signed), else prt::Error naming the line.
void check_face_indices(const std::string& path, std::string_view line, std::size_t line_number) {
  for (std::size_t i = 0; i < line.size();) {
    if (!(line[i] == '-' || (line[i] >= '0' && line[i] <= '9'))) {
      ++i;
      continue;
    }
    long long value = 0;
    const auto [ptr, ec] = std::from_chars(line.data() + i, line.data() + line.size(), value);
    const std::size_t length = std::size_t(ptr - (line.data() + i));
    if (ec == std::errc::result_out_of_range || value > std::numeric_limits<std::int32_t>::max() ||
        value < -std::numeric_limits<std::int32_t>::max())
      fail_file(path, "line " + std::to_string(line_number) + ": face index \"" +
                          std::string(line.substr(i, std::min<std::size_t>(length, 30))) + "\" is out of range");
    i += std::max<std::size_t>(length, 1);
  }
}

enum class Number { ok, missing, malformed, non_finite };

/// The next blank-separated token of text[at, end) as a float, correctly rounded (from_chars; an
/// overflow is non-finite, an underflow rounds to zero or a denormal as strtod gives it); `at` moves
/// past it.
Number next_float(const std::string& text, std::size_t& at, std::size_t end, float& out) {
  while (at < end && (text[at] == ' ' || text[at] == '\t')) ++at;
  std::size_t token_end = at;
  while (token_end < end && text[token_end] != ' ' && text[token_end] != '\t') ++token_end;
  if (token_end == at) return Number::missing;
  const char* first = text.data() + at + (text[at] == '+' ? 1 : 0);
  const char* last = text.data() + token_end;
  at = token_end;
  auto [ptr, ec] = std::from_chars(first, last, out);
  if (ec == std::errc::result_out_of_range && ptr == last) {
    const double value = std::strtod(std::string(first, last).c_str(), nullptr);
    if (!(std::abs(value) <= double(std::numeric_limits<float>::max()))) return Number::non_finite;
    out = float(value);
  } else if (ec != std::errc() || ptr != last || first == last) {
    return Number::malformed;
  }
  return std::isfinite(out) ? Number::ok : Number::non_finite;
}

/// The OBJ lines whose numbers prt checks itself (tinyobjloader reads "nan" or "abc" as 0 without
/// a word): their tag, what one is called in errors, how many numbers it must have and may have.
struct StrictLine {
  const char* tag;
  const char* what;
  const char* value;
  int required, checked;
};
constexpr StrictLine kStrictLines[] = {{"v", "vertex", "position", 3, 3},
                                       {"vt", "texture coordinate", "value", 1, 3},
                                       {"vn", "normal", "direction", 3, 3}};

/// The numbers of the line text[start, end) after its tag (which ends at `at`), or prt::Error naming
/// the file, the line and the element (1-based `number` of its kind) for a missing, malformed or
/// non-finite one.
glm::vec3 strict_numbers(const std::string& path, const std::string& text, std::size_t start, std::size_t at,
                         std::size_t end, const StrictLine& kind, std::size_t line_number, std::size_t number) {
  glm::vec3 values(0.0f);
  for (int c = 0; c < kind.checked; ++c) {
    const Number n = next_float(text, at, end, values[c]);
    if (n == Number::ok || (n == Number::missing && c >= kind.required)) continue;
    fail_file(path, "line " + std::to_string(line_number) + ": " + kind.what + " " + std::to_string(number) +
                        " (1-based) has " + (n == Number::non_finite ? "a non-finite " : "a malformed ") + kind.value + " \"" +
                        text.substr(start, std::min<std::size_t>(end - start, 60)) + "\"");
  }
  return values;
}

/// The "v" lines' positions, parsed strictly (strict_numbers; "vt" and "vn" lines are checked the
/// same way, face indices by check_face_indices). Lines are split as tinyobjloader splits them (\n,
/// \r\n or \r), and a line's tag is its first non-blank characters up to a space or tab.
std::vector<glm::vec3> strict_positions(const std::string& path, const std::string& text) {
  std::vector<glm::vec3> positions;
  std::size_t counts[std::size(kStrictLines)] = {};
  std::size_t line_number = 0, pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find_first_of("\r\n", pos);
    if (end == std::string::npos) end = text.size();
    ++line_number;
    std::size_t i = pos;
    while (i < end && (text[i] == ' ' || text[i] == '\t')) ++i;
    std::size_t tag_end = i;
    while (tag_end < end && text[tag_end] != ' ' && text[tag_end] != '\t') ++tag_end;
    const std::string_view tag = std::string_view(text).substr(i, tag_end - i);
    if (tag == "f" && tag_end < end)
      check_face_indices(path, std::string_view(text).substr(tag_end, end - tag_end), line_number);
    for (std::size_t k = 0; k < std::size(kStrictLines); ++k) {
      if (tag != kStrictLines[k].tag || tag_end == end) continue;
      const glm::vec3 values = strict_numbers(path, text, i, tag_end, end, kStrictLines[k], line_number, ++counts[k]);
      if (k == 0) positions.push_back(values);
    }
    pos = end + 1;
    if (end < text.size() && text[end] == '\r' && pos < text.size() && text[pos] == '\n') ++pos;
  }
  return positions;
}

}  // namespace

namespace {

struct ObjData {
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::map<std::string, MtlPbr> pbr;  ///< the MTL files' Pr, Pm, map_Pr and map_Pm (scan_mtl_pbr)
};

/// The OBJ's folder with a trailing '/', or "" for a file in the working folder: where MTL names resolve.
std::string obj_folder(const std::string& path) {
  std::string folder = std::filesystem::path(path).parent_path().string();
  if (!folder.empty()) folder += "/";
  return folder;
}

/// MTL files for tinyobjloader, read through read_file (so a FIFO or device is refused as every input
/// is) and resolved against the OBJ's folder as written (tinyobjloader's own reader splits its base
/// folder at ':'). A missing file is a warning, as in tinyobjloader; any other problem an Error.
class MtlReader : public tinyobj::MaterialReader {
 public:
  MtlReader(std::string folder, std::map<std::string, MtlPbr>* pbr) : folder_(std::move(folder)), pbr_(pbr) {}
  bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                  std::map<std::string, int>* names, std::string* warn, std::string* err) override {
    const std::string file = folder_ + name;
    std::error_code ec;
    if (!std::filesystem::exists(file, ec)) {
      if (warn) *warn += "Material file [ " + name + " ] not found\n";
      return false;
    }
    const std::string bytes = read_file(file);
    scan_mtl_pbr(file, bytes, pbr_);
    std::istringstream text(bytes);
    tinyobj::LoadMtl(names, materials, &text, warn, err);
    return true;
  }

 private:
  std::string folder_;
  std::map<std::string, MtlPbr>* pbr_;
};

}  // namespace

std::vector<std::string> obj_referenced_files(const std::string& path) {
  const std::string text = read_file(path);
  std::vector<std::string> files;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ' || line.back() == '\t')) line.pop_back();
    const std::size_t i = line.find_first_not_of(" \t");
    if (i == std::string::npos || line.compare(i, 7, "mtllib ") != 0) continue;
    // tinyobjloader's split: names separated by spaces, a backslash escapes the next character.
    std::string name;
    bool escaped = false;
    for (std::size_t k = i + 7; k <= line.size(); ++k) {
      const char ch = k < line.size() ? line[k] : ' ';
      if (!escaped && ch == '\\') {
        escaped = true;
        continue;
      }
      if (!escaped && ch == ' ') {
        if (!name.empty()) files.push_back(obj_folder(path) + name);
        name.clear();
      } else {
        name += ch;
      }
      escaped = false;
    }
  }
  const std::size_t mtl_count = files.size();
  for (std::size_t i = 0; i < mtl_count; ++i) {
    const std::vector<std::string> textures = mtl_texture_files(files[i], obj_folder(path));
    files.insert(files.end(), textures.begin(), textures.end());
  }
  return files;
}

namespace {

// Parses the file (and its MTL files) with tinyobjloader; the positions come from the strict scan.
ObjData read_obj(const std::string& path, RawMesh* raw) {
  const std::string text = read_file(path);
  std::vector<glm::vec3> positions = strict_positions(path, text);
  ObjData obj;
  std::string warn, err;
  std::istringstream stream(text);
  MtlReader mtl(obj_folder(path), &obj.pbr);
  // triangulate = false: prt fan-triangulates itself (and tinyobjloader's triangulation would index
  // vertices before prt has range-checked them). default_vcols_fallback = false: colours are ignored.
  const bool ok = tinyobj::LoadObj(&obj.attrib, &obj.shapes, &obj.materials, &warn, &err, &stream, &mtl,
                                   /*triangulate=*/false, /*default_vcols_fallback=*/false);
  if (!ok) fail_file(path, "cannot read OBJ: " + first_line(err.empty() ? warn : err));
  if (!first_line(warn).empty()) raw->notes_only.notes.push_back("OBJ reader: " + first_line(warn));
  const std::size_t vertex_count = obj.attrib.vertices.size() / 3;
  if (vertex_count >= std::numeric_limits<std::uint32_t>::max()) fail_file(path, "too many vertices");
  if (positions.size() == vertex_count) {
    raw->positions = std::move(positions);
  } else {  // not expected: the two readers disagree on which lines are "v" lines; trust tinyobjloader
    raw->positions.resize(vertex_count);
    for (std::size_t i = 0; i < vertex_count; ++i)
      raw->positions[i] =
          glm::vec3(obj.attrib.vertices[3 * i], obj.attrib.vertices[3 * i + 1], obj.attrib.vertices[3 * i + 2]);
  }
  return obj;
}

struct FaceRefs {
  DistinctPairs position_materials;
  bool any_material = false;
  std::size_t corners_without_uv = 0;
};

// The corner's "vt" as (u, 1 - v) (prt's v points down, OBJ's up), range-checked; (0, 0) and a
// count in refs when the corner has none.
glm::vec2 corner_uv(const std::string& path, const ObjData& obj, const tinyobj::index_t& corner, std::size_t face_number,
                    FaceRefs* refs) {
  if (corner.texcoord_index < 0) {
    if (corner.texcoord_index < -1)
      fail_file(path, "face " + std::to_string(face_number) + " refers to a texture coordinate before the first");
    ++refs->corners_without_uv;
    return glm::vec2(0.0f);
  }
  const std::size_t t = std::size_t(corner.texcoord_index);
  if (t >= obj.attrib.texcoords.size() / 2)
    fail_file(path, "face " + std::to_string(face_number) + " refers to texture coordinate " + std::to_string(t + 1) +
                        " (1-based), but the file has " + std::to_string(obj.attrib.texcoords.size() / 2));
  return glm::vec2(obj.attrib.texcoords[2 * t], 1.0f - obj.attrib.texcoords[2 * t + 1]);
}

// Range-checks one face corner's vertex and normal indices; face_number names it in errors.
void check_corner(const std::string& path, const tinyobj::index_t& corner, std::size_t face_number,
                  std::size_t vertex_count, std::size_t normal_count) {
  if (corner.vertex_index < 0)
    fail_file(path, "face " + std::to_string(face_number) + " refers to a vertex before the first");
  if (std::size_t(corner.vertex_index) >= vertex_count)
    fail_file(path, "face " + std::to_string(face_number) + " refers to vertex " +
                        std::to_string(corner.vertex_index + 1) + " (1-based), but the file has " +
                        std::to_string(vertex_count) + " vertices");
  if (corner.normal_index < -1 || (corner.normal_index >= 0 && std::size_t(corner.normal_index) >= normal_count))
    fail_file(path, "face " + std::to_string(face_number) + " refers to normal " +
                        std::to_string(corner.normal_index + 1) + " (1-based), but the file has " +
                        std::to_string(normal_count) + " normals");
}

// Fan-triangulates every face into raw->indices, splitting positions by normal (CornerVertices), and
// collects each vertex's materials.
FaceRefs triangulate_faces(const std::string& path, const ObjData& obj, RawMesh* raw) {
  const std::size_t vertex_count = raw->positions.size(), normal_count = obj.attrib.normals.size() / 3;
  FaceRefs refs;
  CornerVertices vertices(path, obj.attrib.normals, raw);
  std::size_t face_number = 0;
  for (const tinyobj::shape_t& shape : obj.shapes) {
    const tinyobj::mesh_t& m = shape.mesh;
    std::size_t offset = 0;
    for (std::size_t f = 0; f < m.num_face_vertices.size(); ++f, ++face_number) {
      const std::size_t n = m.num_face_vertices[f];
      if (offset + n > m.indices.size())
        fail_file(path, "face " + std::to_string(face_number) + " is malformed (a polygon of more than 255 vertices?)");
      const int material = f < m.material_ids.size() ? m.material_ids[f] : -1;
      if (material >= int(obj.materials.size()))
        fail_file(path, "face " + std::to_string(face_number) + " has an unknown material");
      if (material >= 0) refs.any_material = true;
      std::uint32_t first = 0, previous = 0;
      glm::vec2 first_uv(0.0f), previous_uv(0.0f);
      for (std::size_t j = 0; j < n; ++j) {
        const tinyobj::index_t& corner = m.indices[offset + j];
        check_corner(path, corner, face_number, vertex_count, normal_count);
        const glm::vec2 uv = corner_uv(path, obj, corner, face_number, &refs);
        const std::uint32_t index = vertices.vertex_of(corner.vertex_index, corner.normal_index);
        refs.position_materials.add(index, material);
        if (j == 0) first = index, first_uv = uv;
        if (j >= 2) {  // fan
          raw->indices.insert(raw->indices.end(), {first, previous, index});
          raw->corner_uv.insert(raw->corner_uv.end(), {first_uv, previous_uv, uv});
          raw->triangle_material.push_back(material >= 0 ? std::uint32_t(material) : std::uint32_t(obj.materials.size()));
        }
        previous = index;
        previous_uv = uv;
      }
      if (n < 3) ++raw->skipped_polygons;
      offset += n;
    }
  }
  vertices.finish();
  return refs;
}

// Per position, the mean over the distinct materials of its faces of value(material) (material -1:
// a face without one gives `none`). Positions of no face get `unused`.
template <class Value>
std::vector<glm::vec3> material_mean(DistinctPairs& position_materials, std::size_t vertex_count, Value value,
                                     const glm::dvec3& none, const glm::vec3& unused) {
  std::vector<glm::dvec3> sums(vertex_count, glm::dvec3(0.0));
  std::vector<int> counts(vertex_count, 0);
  position_materials.for_each([&](std::uint32_t position, int material) {
    sums[position] += material >= 0 ? value(material) : none;
    counts[position] += 1;
  });
  std::vector<glm::vec3> out(vertex_count, unused);
  for (std::size_t i = 0; i < vertex_count; ++i)
    if (counts[i] > 0) out[i] = glm::vec3(sums[i] / double(counts[i]));
  return out;
}

// Albedo (mean Kd, kDefaultKd without a material) and emission (mean Ke, 0 without a material).
void obj_materials(const ObjData& obj, FaceRefs* refs, RawMesh* raw) {
  if (!refs->any_material) return;
  const std::vector<tinyobj::material_t>& materials = obj.materials;
  const std::size_t vertex_count = raw->positions.size();
  raw->albedo = material_mean(
      refs->position_materials, vertex_count,
      [&](int m) { return glm::dvec3(materials[m].diffuse[0], materials[m].diffuse[1], materials[m].diffuse[2]); },
      glm::dvec3(kDefaultKd), glm::vec3(kDefaultKd));
  bool any_emission = false;
  for (const tinyobj::material_t& m : materials)
    any_emission = any_emission || m.emission[0] != 0 || m.emission[1] != 0 || m.emission[2] != 0;
  if (!any_emission) return;
  raw->emission = material_mean(
      refs->position_materials, vertex_count,
      [&](int m) { return glm::dvec3(materials[m].emission[0], materials[m].emission[1], materials[m].emission[2]); },
      glm::dvec3(0.0), glm::vec3(0.0f));
}

}  // namespace

RawMesh load_obj(const std::string& path) {
  RawMesh raw;
  const ObjData obj = read_obj(path, &raw);
  FaceRefs refs = triangulate_faces(path, obj, &raw);
  if (refs.corners_without_uv > 0) {
    raw.corner_uv.clear();
    raw.missing_uv_reason = obj.attrib.texcoords.empty() ? "the OBJ file has no vt lines"
                                                         : std::to_string(refs.corners_without_uv) + " face corners have no vt";
  }
  obj_materials(obj, &refs, &raw);
  if (refs.any_material) {
    obj_material_list(obj_folder(path), obj.materials, obj.pbr, &raw);
    raw.base_color_uv = raw.corner_uv;
    const bool textured = std::any_of(raw.materials.begin(), raw.materials.end(), [](const Material& m) { return m.textured(); });
    if (textured && raw.base_color_uv.empty())
      raw.notes_only.notes.push_back("map_Kd textures are ignored: " + raw.missing_uv_reason + "; Kd alone is used");
  } else {
    raw.triangle_material.clear();
  }
  return raw;
}

}  // namespace prt::mesh::detail
