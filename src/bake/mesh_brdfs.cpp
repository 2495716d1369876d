// Materials -> per-vertex BRDFs for `--brdf mesh` (mesh_brdfs.h).
#include "bake/mesh_brdfs.h"

#include <algorithm>
#include <cstdio>
#include <map>

namespace prt::bake {

namespace {

constexpr double kMinMeshRoughness = 0.01;  // brdf/brdf.h: the least roughness a ggx lobe takes

// The gltf SPEC string of a material's factors (roughness raised to kMinMeshRoughness).
std::string material_spec(const mesh::Material& m) {
  char text[200];
  std::snprintf(text, sizeof text, "gltf:basecolor=%.9g/%.9g/%.9g,metallic=%.9g,roughness=%.9g", m.base_color_factor.r,
                m.base_color_factor.g, m.base_color_factor.b, m.metallic_factor,
                std::max<double>(m.roughness_factor, kMinMeshRoughness));
  return text;
}

void material_notes(const mesh::Mesh& mesh, std::vector<std::string>* notes) {
  int rough = 0, textured = 0;
  for (const mesh::Material& m : mesh.materials) {
    rough += m.roughness_factor < kMinMeshRoughness;
    textured += m.metallic_roughness_textured || m.textured();
  }
  if (rough > 0)
    notes->push_back(std::to_string(rough) + " materials have roughness below 0.01, which an SH matrix cannot hold; baked with 0.01");
  if (textured > 0)
    notes->push_back(std::to_string(textured) +
                     " materials have base colour or metallic-roughness textures; glossy BRDFs use the factors alone");
}

}  // namespace

brdf::VertexBrdfs mesh_brdfs(const mesh::Mesh& mesh, std::vector<std::string>* notes) {
  brdf::VertexBrdfs out;
  std::map<std::string, std::uint32_t> entry_of_spec;
  std::vector<std::int64_t> entry_of_material(mesh.materials.size(), -1);
  constexpr std::uint32_t kUnset = ~0u;
  out.vertex.assign(mesh.positions.size(), kUnset);
  std::vector<char> mixed(mesh.positions.size(), 0);
  for (std::size_t t = 0; t < mesh.triangle_material.size(); ++t) {
    const std::uint32_t m = mesh.triangle_material[t];
    if (entry_of_material[m] < 0) {
      const std::string spec = material_spec(mesh.materials[m]);
      const auto [it, added] = entry_of_spec.emplace(spec, static_cast<std::uint32_t>(out.table.size()));
      if (added) out.table.push_back(brdf::parse_brdf(spec));
      entry_of_material[m] = it->second;
    }
    const auto entry = static_cast<std::uint32_t>(entry_of_material[m]);
    for (int corner = 0; corner < 3; ++corner) {
      const std::uint32_t q = mesh.indices[3 * t + corner];
      if (out.vertex[q] == kUnset) out.vertex[q] = entry;
      else if (out.vertex[q] != entry) mixed[q] = 1;
    }
  }
  for (std::uint32_t& v : out.vertex)
    if (v == kUnset) v = 0;
  const auto marked = std::count(mixed.begin(), mixed.end(), 1);
  if (marked > 0)
    notes->push_back(std::to_string(marked) + " vertices join triangles of different materials; each takes its first triangle's BRDF");
  material_notes(mesh, notes);
  if (out.table.empty()) out.table.push_back(brdf::parse_brdf(material_spec(mesh.materials[0])));
  if (out.table.size() == 1) out.vertex.clear();
  return out;
}

}  // namespace prt::bake
