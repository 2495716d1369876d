#include "render/mixed_frame.h"

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/text.h"
#include "transfer/mixed_parts.h"

namespace prt::render {

std::vector<std::string> mixed_transfer_paths(const std::string& path) {
  if (lower_extension(path) != ".prt") return {path};
  const transfer::Header header = transfer::read_transfer_header(path);
  const std::optional<transfer::MixedParts> parts = transfer::read_mixed_entry(header, path);
  if (!parts) return {path};
  const std::string partner = transfer::partner_path(path, *parts);
  check_regular_input(partner);
  return parts->role == "texel" ? std::vector<std::string>{path, partner} : std::vector<std::string>{partner, path};
}

TriangleRuns mixed_vertex_runs(const SceneInputs& scene, std::size_t texel_index) {
  if (texel_index + 1 >= scene.transfers.size()) fail("mixed_vertex_runs: a mixed scene has two transfers");
  const std::string& texel_path = scene.transfer_paths[texel_index];
  const std::string& vertex_path = scene.transfer_paths[texel_index + 1];
  const std::optional<transfer::MixedParts> texel = transfer::read_mixed_entry(scene.transfers[texel_index].header, texel_path);
  const std::optional<transfer::MixedParts> vertex = transfer::read_mixed_entry(scene.transfers[texel_index + 1].header, vertex_path);
  if (!texel || texel->role != "texel") fail_file(texel_path, "is not the texel file of a mixed pair");
  if (!vertex || vertex->role != "vertex") fail_file(vertex_path, "is not the per-vertex file of a mixed pair");
  if (texel->vertex_runs != vertex->vertex_runs)
    fail_file(vertex_path, "lists other per-vertex triangles than its partner " + texel_path + " (not baked together)");
  transfer::vertex_triangle_mask(*texel, scene.mesh.triangle_count(), texel_path);  // throws for a run past the mesh
  return texel->vertex_runs;
}

}  // namespace prt::render
