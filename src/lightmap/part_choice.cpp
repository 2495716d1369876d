#include "lightmap/part_choice.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "core/error.h"
#include "lightmap/uv_validation.h"

namespace prt::lightmap {

namespace {

// The part of each triangle (0 for a mesh without glTF primitives), the parts' descriptions and node names.
std::vector<std::uint32_t> triangle_parts(const mesh::Mesh& mesh, std::vector<std::string>& parts, std::vector<std::string>& nodes) {
  std::vector<std::uint32_t> part(mesh.triangle_count(), 0);
  if (mesh.triangle_source.size() != mesh.triangle_count() || mesh.source_primitives.empty()) {
    parts = {"mesh"};
    nodes = {""};
    return part;
  }
  for (const mesh::SourcePrimitive& p : mesh.source_primitives) {
    parts.push_back(mesh::describe_primitive(p));
    nodes.push_back(p.node_name);
  }
  for (std::size_t t = 0; t < part.size(); ++t) part[t] = mesh.triangle_source[t].primitive;
  return part;
}

double uv_area(const mesh::Mesh& mesh, std::size_t t) {
  const glm::vec2* uv = mesh.lightmap_uv.data() + 3 * t;
  for (int k = 0; k < 3; ++k)
    if (!(uv[k].x >= -kUvHair && uv[k].x <= 1.0f + kUvHair && uv[k].y >= -kUvHair && uv[k].y <= 1.0f + kUvHair)) return 0.0;
  const glm::dvec2 a(uv[1] - uv[0]), b(uv[2] - uv[0]);
  return 0.5 * std::abs(a.x * b.y - a.y * b.x);
}

// auto: per texel where the part's texels (UV area x W x H) outnumber its distinct vertices.
std::vector<std::uint8_t> auto_texel_parts(const mesh::Mesh& mesh, const std::vector<std::uint32_t>& part, std::size_t parts,
                                           int width, int height) {
  std::vector<double> texels(parts, 0.0);
  std::vector<std::set<std::uint32_t>> vertices(parts);
  for (std::size_t t = 0; t < part.size(); ++t) {
    texels[part[t]] += uv_area(mesh, t) * double(width) * double(height);
    for (int k = 0; k < 3; ++k) vertices[part[t]].insert(mesh.indices[3 * t + k]);
  }
  std::vector<std::uint8_t> texel(parts, 0);
  for (std::size_t p = 0; p < parts; ++p) texel[p] = texels[p] > double(vertices[p].size());
  return texel;
}

std::vector<std::uint8_t> named_texel_parts(const std::vector<std::string>& parts, const std::vector<std::string>& nodes,
                                            const std::string& spec, const std::string& mesh_path) {
  std::vector<std::uint8_t> texel(parts.size(), 0);
  auto fail_names = [&](const std::string& what) { fail_file(mesh_path, "--texel-parts: " + what); };
  if (parts.size() == 1 && parts[0] == "mesh")
    fail_names("names need a glTF scene with named nodes; this file is one part (use all or auto)");
  std::size_t start = 0;
  while (start <= spec.size()) {
    const std::size_t comma = std::min(spec.find(',', start), spec.size());
    const std::string name = spec.substr(start, comma - start);
    if (name.empty()) fail_names("empty name in '" + spec + "'");
    bool found = false;
    for (std::size_t p = 0; p < parts.size(); ++p)
      if (nodes[p] == name || parts[p] == name) texel[p] = 1, found = true;
    if (!found) {
      std::string known;
      for (const std::string& node : nodes) known += (known.empty() ? "" : ", ") + ("\"" + node + "\"");
      fail_names("no part named \"" + name + "\" (node names: " + known + ")");
    }
    start = comma + 1;
  }
  return texel;
}

}  // namespace

bool PartChoice::mixed() const { return std::find(vertex_triangle.begin(), vertex_triangle.end(), 1) != vertex_triangle.end(); }

PartChoice choose_parts(const mesh::Mesh& mesh, const std::string& spec, int width, int height, const std::string& mesh_path) {
  std::vector<std::string> parts, nodes;
  const std::vector<std::uint32_t> part = triangle_parts(mesh, parts, nodes);
  std::vector<std::uint8_t> texel(parts.size(), 1);
  if (spec == "auto") texel = auto_texel_parts(mesh, part, parts.size(), width, height);
  else if (spec != "all") texel = named_texel_parts(parts, nodes, spec, mesh_path);
  if (std::find(texel.begin(), texel.end(), 1) == texel.end())
    fail_file(mesh_path, "--texel-parts " + spec + ": no part is baked per texel; bake per vertex without --lightmap");
  std::vector<double> texel_uv_area(parts.size(), 0.0);
  std::vector<std::size_t> triangles(parts.size(), 0);
  for (std::size_t t = 0; t < part.size(); ++t) texel_uv_area[part[t]] += uv_area(mesh, t), ++triangles[part[t]];
  // `all` is a plain lightmap bake: its UV checks (uv_validation.h) name the problem in full.
  for (std::size_t p = 0; p < parts.size() && spec != "all"; ++p)
    if (texel[p] && triangles[p] > 0 && !(texel_uv_area[p] > 0.0))
      fail_file(mesh_path, "--texel-parts " + spec + ": part " + parts[p] +
                               " has no usable lightmap UVs (every triangle has zero UV area or UVs outside [0,1]); bake it per vertex");
  PartChoice choice;
  choice.vertex_triangle.resize(part.size());
  for (std::size_t t = 0; t < part.size(); ++t) choice.vertex_triangle[t] = !texel[part[t]];
  for (std::size_t p = 0; p < parts.size(); ++p) (texel[p] ? choice.texel_parts : choice.vertex_parts).push_back(parts[p]);
  return choice;
}

}  // namespace prt::lightmap
