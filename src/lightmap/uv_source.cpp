#include "lightmap/uv_source.h"

#include <algorithm>

#include "core/error.h"
#include "lightmap/rasterize.h"
#include "lightmap/uv_validation.h"

namespace prt::lightmap {

UvMode parse_uv_mode(const std::string& text) {
  if (text == "file") return UvMode::file;
  if (text == "auto") return UvMode::automatic;
  if (text == "generate") return UvMode::generate;
  fail_option("uv", " " + text + ": expected file, auto or generate");
}

namespace {

// Empty when the file's UVs are usable (uv_validation.h), else why not.
std::string why_not_usable(const mesh::Mesh& mesh, const LightmapOptions& lightmap, int threads) {
  if (!mesh.has_lightmap_uv()) return "the file has no lightmap UVs: " + lightmap.missing_uv_reason;
  std::vector<std::uint8_t> skip;
  UvProblems problems = check_texel_uvs(mesh, lightmap.vertex_triangles, skip);
  if (problems.tiling()) return problems.problems(mesh);
  const TexelSamples samples =
      rasterize(mesh, std::vector<glm::vec3>(mesh.vertex_count(), glm::vec3(1.0f)), lightmap.width, lightmap.height, threads, &skip);
  add_raster_checks(problems, samples);
  return problems.refused() ? problems.problems(mesh) : std::string();
}

}  // namespace

void choose_lightmap_uvs(mesh::Mesh& mesh, UvMode mode, const LightmapOptions& lightmap, int threads, UvSourceReport* report) {
  UvSourceReport local;
  UvSourceReport& rep = report ? *report : local;
  rep = UvSourceReport{};
  if (mode == UvMode::file) return;
  rep.reason = mode == UvMode::generate ? "--uv generate" : why_not_usable(mesh, lightmap, threads);
  if (rep.reason.empty()) return;
  unwrap::UnwrapOptions options;
  options.width = lightmap.width;
  options.height = lightmap.height;
  options.padding = std::max(1, lightmap.gutter);
  options.threads = threads;
  options.mesh_path = lightmap.mesh_path;
  mesh.lightmap_uv = unwrap::unwrap(mesh, options, &rep.unwrap);
  mesh.lightmap_uv_set = 1;
  rep.generated = true;
}

}  // namespace prt::lightmap
