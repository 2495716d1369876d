#include "lightmap/lightmap_shading.h"

#include "lightmap/gutter.h"
#include "lightmap/texel_bake.h"
#include "shade/surface_albedo.h"
#include "trace/scene.h"
#include "trace/true_surface.h"

namespace prt::lightmap {

image::Image shade_lightmap(const mesh::Mesh& mesh, const transfer::TransferData& transfer, const light::SceneLighting& lighting,
                            const std::string& origin, const shade::DiscShadingOptions& options, shade::SplitReport* report) {
  const transfer::Header& h = transfer.header;
  transfer::check_mesh_match(origin, h, mesh.vertex_count(), mesh.triangle_count(), mesh::fingerprint(mesh));
  transfer::check_uv_match(origin, h, mesh::uv_fingerprint(mesh));
  const BakedLightmap baked = baked_lightmap(h, origin);
  const trace::Scene scene(mesh, trace::SceneOptions{options.threads, true});
  const TexelSamples samples =
      texel_samples(mesh, scene, shade::surface_albedo(mesh, h, origin), baked.options, baked.seed, options.threads);
  // The covered texels as a per-point transfer over a mesh of the sample points (no triangles): the
  // vertex shading path, with shadow rays against the real scene.
  const std::size_t stride = h.values_per_vertex();
  mesh::Mesh points;
  std::vector<glm::vec3> geometric_normals;  // of each sample's triangle: the true-surface rule of its disc rays
  transfer::TransferData per_point;
  per_point.header = h;
  per_point.header.texel_width = per_point.header.texel_height = 0;
  per_point.header.vertex_count = samples.samples.size();
  per_point.header.parameters_json = R"({"albedo": "mesh"})";
  for (const TexelSample& s : samples.samples) {
    points.positions.push_back(s.position);
    points.normals.push_back(s.normal);
    points.albedo.push_back(s.albedo);
    geometric_normals.push_back(glm::vec3(trace::triangle_normal(mesh, s.triangle)));
    const auto block = transfer.values.begin() + std::ptrdiff_t(s.texel * stride);
    per_point.values.insert(per_point.values.end(), block, block + std::ptrdiff_t(stride));
    if (!transfer.bounce_only.empty()) {
      const auto bounce = transfer.bounce_only.begin() + std::ptrdiff_t(s.texel * stride);
      per_point.bounce_only.insert(per_point.bounce_only.end(), bounce, bounce + std::ptrdiff_t(stride));
    }
  }
  shade::DiscShadingOptions disc = options;
  disc.geometric_normals = &geometric_normals;
  const std::vector<glm::vec3> lit = shade::shade_diffuse_split(points, per_point, lighting, origin, disc, report, &scene);
  image::Image out(baked.options.width, baked.options.height, 3);
  std::vector<float> grid(out.pixels.size(), 0.0f);
  for (std::size_t k = 0; k < samples.samples.size(); ++k)
    for (int c = 0; c < 3; ++c) grid[std::size_t(samples.samples[k].texel) * 3 + std::size_t(c)] = lit[k][c];
  fill_gutter(grid, 3, transfer.coverage, gutter_rounds(transfer.coverage, out.width, out.height, baked.options.gutter), out.width, out.height);
  out.pixels = std::move(grid);
  return out;
}

}  // namespace prt::lightmap
