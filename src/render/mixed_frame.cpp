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

std::vector<std::uint8_t> mixed_vertex_triangles(const SceneInputs& scene) {
  if (scene.transfers.size() != 2) fail("mixed_vertex_triangles: a mixed scene has two transfers");
  const std::string& texel_path = scene.transfer_paths[0];
  const std::string& vertex_path = scene.transfer_paths[1];
  const std::optional<transfer::MixedParts> texel = transfer::read_mixed_entry(scene.transfers[0].header, texel_path);
  const std::optional<transfer::MixedParts> vertex = transfer::read_mixed_entry(scene.transfers[1].header, vertex_path);
  if (!texel || texel->role != "texel") fail_file(texel_path, "is not the texel file of a mixed pair");
  if (!vertex || vertex->role != "vertex") fail_file(vertex_path, "is not the per-vertex file of a mixed pair");
  if (texel->vertex_runs != vertex->vertex_runs)
    fail_file(vertex_path, "lists other per-vertex triangles than its partner " + texel_path + " (not baked together)");
  return transfer::vertex_triangle_mask(*texel, scene.mesh.triangle_count(), texel_path);
}

void composite_mixed(image::Image& frame, const image::Image& vertex_frame, const std::vector<std::uint32_t>& ids,
                     const std::vector<std::uint8_t>& vertex_triangle) {
  const std::size_t pixels = std::size_t(frame.width) * std::size_t(frame.height);
  for (std::size_t p = 0; p < pixels && p < ids.size(); ++p) {
    if (ids[p] == kNoTriangle || ids[p] >= vertex_triangle.size() || !vertex_triangle[ids[p]]) continue;
    for (int c = 0; c < frame.channels; ++c) frame.pixels[p * frame.channels + c] = vertex_frame.pixels[p * frame.channels + c];
  }
}

image::Image render_mixed(Renderer& renderer, FrameSettings settings, int texel, int vertex,
                          const std::vector<std::uint8_t>& vertex_triangle, int width, int height) {
  settings.transfer = texel;
  renderer.render(settings, width, height);
  image::Image frame = renderer.read_radiance();
  const std::vector<std::uint32_t> ids = renderer.read_triangle_ids();
  settings.transfer = vertex;
  renderer.render(settings, width, height);
  composite_mixed(frame, renderer.read_radiance(), ids, vertex_triangle);
  return frame;
}

}  // namespace prt::render
