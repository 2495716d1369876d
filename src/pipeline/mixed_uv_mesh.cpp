#include "pipeline/mixed_uv_mesh.h"

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <numeric>

#include "core/error.h"
#include "mesh/engine_gltf.h"

namespace prt::pipeline {

namespace {

// The source triangle of each triangle of the file: grouped by material, then by kind (stable), as the
// file's one primitive per material and kind holds them.
std::vector<std::size_t> file_triangle_order(const mesh::Mesh& mesh, const std::vector<std::uint8_t>& vertex_triangle) {
  std::vector<std::size_t> order(mesh.triangle_count());
  std::iota(order.begin(), order.end(), std::size_t{0});
  const bool materials = mesh.triangle_material.size() == order.size();
  const auto key = [&](std::size_t t) {
    return std::make_pair(materials ? mesh.triangle_material[t] : 0u, t < vertex_triangle.size() ? vertex_triangle[t] : 0);
  };
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return key(a) < key(b); });
  return order;
}

bool same_corners(const mesh::Mesh& a, std::size_t ta, const mesh::Mesh& b, std::size_t tb) {
  for (int k = 0; k < 3; ++k)
    if (std::memcmp(&a.positions[a.indices[3 * ta + k]], &b.positions[b.indices[3 * tb + k]], sizeof(glm::vec3)) != 0) return false;
  return true;
}

}  // namespace

std::string mixed_mesh_path(const std::string& texel_path) {
  const std::filesystem::path path(texel_path);
  return (path.parent_path() / (path.stem().string() + ".mesh.glb")).string();
}

MixedUvMesh::MixedUvMesh(const std::string& path, const std::string& source_path, const mesh::Mesh& mesh,
                         const std::vector<std::uint8_t>& vertex_triangle)
    : file_(std::make_unique<AtomicFile>(path)) {
  mesh::EngineExtras extras;  // the mesh as loaded, in prt unwrap's OBJ/PLY layout (docs/formats.md, "Unwrapped mesh")
  extras.lightmap_set = 1;
  extras.as_loaded = true;
  extras.triangle_group = vertex_triangle;  // one primitive per material and kind: the engine glTF keeps primitives whole
  write_staged(*file_, [&](const std::string& temp) { mesh::write_engine_glb(temp, source_path, mesh, extras); });
  try {
    loaded_ = mesh::load_mesh(file_->temp_path(), mesh::LoadOptions{mesh::kDefaultScene, true});
  } catch (const Error& e) {
    fail_file(path, std::string("cannot load the mesh written with the generated UVs back: ") + e.what());
  }
  const std::vector<std::size_t> order = file_triangle_order(mesh, vertex_triangle);
  bool same = loaded_.triangle_count() == order.size() && loaded_.lightmap_uv.size() == loaded_.indices.size();
  vertex_triangle_.assign(order.size(), 0);
  for (std::size_t t = 0; same && t < order.size(); ++t) {
    same = same_corners(loaded_, t, mesh, order[t]);
    vertex_triangle_[t] = order[t] < vertex_triangle.size() ? vertex_triangle[order[t]] : 0;
  }
  if (!same)
    fail_file(path, "the mesh written with the generated lightmap UVs does not load back with the source's triangles; "
                    "write the UVs with prt unwrap and bake that file");
}

}  // namespace prt::pipeline
