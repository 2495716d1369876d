#include "shade/scene_shading.h"

#include <memory>

#include <glm/geometric.hpp>

#include "shade/glossy.h"
#include "shade/shade.h"
#include "shade/surface_albedo.h"
#include "trace/scene.h"

namespace prt::shade {

namespace {

bool is_interreflected(transfer::Kind kind) {
  return kind == transfer::Kind::interreflected || kind == transfer::Kind::glossy_interreflected;
}

std::unique_ptr<trace::Scene> shadow_scene(const mesh::Mesh& mesh, const transfer::Header& header, int threads) {
  if (header.kind == transfer::Kind::unshadowed) return nullptr;
  return std::make_unique<trace::Scene>(mesh, trace::SceneOptions{threads, true});
}

// The bounce-only part as a transfer of its own (same header), or nullptr with a warning when the file
// has none although its kind interreflects.
std::unique_ptr<transfer::TransferData> bounce_part(const transfer::TransferData& transfer, const std::string& origin,
                                                    SplitReport* report) {
  if (!is_interreflected(transfer.header.kind)) return nullptr;
  if (transfer.bounce_only.empty()) {
    if (report)
      report->warning = origin + ": no bounce-only section (a version 1 file): the discs' interreflected light is left out; "
                                 "re-bake for it";
    return nullptr;
  }
  auto part = std::make_unique<transfer::TransferData>();
  part->header = transfer.header;
  part->header.bounce_only_section = false;
  part->values = transfer.bounce_only;
  return part;
}

void add_into(std::vector<glm::vec3>& to, const std::vector<glm::vec3>& from) {
  for (std::size_t i = 0; i < to.size(); ++i) to[i] += from[i];
}

// The split lighting's output: no negative channel (see the header).
std::vector<glm::vec3> clamped(std::vector<glm::vec3> radiance, const light::SceneLighting& lighting) {
  if (!lighting.clamp_negative) return radiance;
  for (glm::vec3& r : radiance) r = glm::max(r, glm::vec3(0.0f));
  return radiance;
}

}  // namespace

std::vector<glm::vec3> shade_diffuse_split(const mesh::Mesh& mesh, const transfer::TransferData& transfer,
                                           const light::SceneLighting& lighting, const std::string& origin,
                                           const DiscShadingOptions& options, SplitReport* report,
                                           const trace::Scene* shadow_scene_given) {
  std::vector<glm::vec3> out = shade_diffuse(transfer, lighting.sky);
  if (lighting.discs.empty()) return clamped(std::move(out), lighting);
  if (const auto bounce = bounce_part(transfer, origin, report))
    add_into(out, shade_diffuse(*bounce, light::discs_coefficients(lighting.sky.bands, lighting.discs)));
  const auto scene = shadow_scene_given ? nullptr : shadow_scene(mesh, transfer.header, options.threads);
  const trace::Scene* shadows = transfer.header.kind == transfer::Kind::unshadowed ? nullptr
                                : shadow_scene_given                               ? shadow_scene_given
                                                                                   : scene.get();
  const auto footprints = mesh::footprints_for(mesh, baked_footprint(transfer.header, origin));
  DiscShadingOptions disc = options;
  disc.footprints = footprints.get();
  add_into(out, disc_direct_diffuse(mesh, surface_albedo(mesh, transfer.header, origin), lighting.discs, shadows, disc));
  return clamped(std::move(out), lighting);
}

std::vector<glm::vec3> shade_glossy_split(const mesh::Mesh& mesh, const transfer::TransferData& transfer,
                                          const brdf::Brdf& surface, const brdf::BrdfMatrix& matrix,
                                          const light::SceneLighting& lighting, const glm::vec3& eye,
                                          const std::string& origin, const DiscShadingOptions& options,
                                          SplitReport* report) {
  std::vector<glm::vec3> out = shade_glossy_eye(transfer, matrix, lighting.sky, mesh.positions, mesh.normals, eye);
  if (lighting.discs.empty()) return clamped(std::move(out), lighting);
  if (const auto bounce = bounce_part(transfer, origin, report))
    add_into(out, shade_glossy_eye(*bounce, matrix, light::discs_coefficients(lighting.sky.bands, lighting.discs),
                                   mesh.positions, mesh.normals, eye));
  std::vector<glm::vec3> view(mesh.positions.size());
  for (std::size_t v = 0; v < view.size(); ++v) {
    const glm::vec3 d = eye - mesh.positions[v];
    view[v] = glm::length(d) > 0.0f ? glm::normalize(d) : mesh.normals[v];
  }
  const auto scene = shadow_scene(mesh, transfer.header, options.threads);
  const auto footprints = mesh::footprints_for(mesh, baked_footprint(transfer.header, origin));
  DiscShadingOptions disc = options;
  disc.footprints = footprints.get();
  add_into(out, disc_direct_glossy(mesh, surface, lighting.discs, view, scene.get(), disc));
  return clamped(std::move(out), lighting);
}

std::vector<glm::vec3> shade_glossy_vertex_brdfs(const mesh::Mesh& mesh, const transfer::TransferData& transfer,
                                                 const brdf::VertexBrdfs& brdfs, const light::SceneLighting& lighting,
                                                 const glm::vec3& eye, const std::string& origin,
                                                 const DiscShadingOptions& options, SplitReport* report) {
  std::vector<glm::vec3> out(mesh.positions.size());
  for (std::size_t k = 0; k < brdfs.table.size(); ++k) {
    const brdf::BrdfMatrix matrix = brdf::project(brdfs.table[k], static_cast<int>(transfer.header.bands_out));
    const std::vector<glm::vec3> shaded =
        shade_glossy_split(mesh, transfer, brdfs.table[k], matrix, lighting, eye, origin, options, report);
    for (std::size_t v = 0; v < out.size(); ++v)
      if (brdfs.of(v) == k) out[v] = shaded[v];
  }
  return out;
}

}  // namespace prt::shade
