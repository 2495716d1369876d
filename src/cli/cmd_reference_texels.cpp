#include "cli/cmd_reference_texels.h"

#include <cstdio>

#include "bake/bake.h"
#include "cli/distributed.h"
#include "image/image.h"
#include "lightmap/texel_bake.h"
#include "trace/scene.h"
#include "transfer/transfer_file.h"

namespace prt::cli {

void run_reference_texels(const mesh::Mesh& mesh, const std::string& mesh_path, const reference::EnvironmentSampler& sampler,
                          const reference::ReferenceOptions& options, const std::string& texels_path, const std::string& output,
                          bool quiet) {
  const transfer::Header header = transfer::read_transfer_header(texels_path);
  transfer::check_mesh_match(texels_path, header, mesh.vertex_count(), mesh.triangle_count(), mesh::fingerprint(mesh));
  transfer::check_uv_match(texels_path, header, mesh::uv_fingerprint(mesh));
  lightmap::BakedLightmap baked = lightmap::baked_lightmap(header, texels_path);
  baked.options.mesh_path = mesh_path;
  const std::vector<glm::vec3> albedo = reference::reference_albedo(mesh, options.albedo);
  std::vector<reference::PointSample> points;
  lightmap::TexelSamples samples;
  {
    const trace::Scene scene(mesh, trace::SceneOptions{1, true});
    samples = lightmap::texel_samples(mesh, scene, albedo, baked.options, baked.seed, options.threads);
  }
  for (const lightmap::TexelSample& s : samples.samples) points.push_back({s.position, s.normal, s.albedo, s.triangle});
  reference::ReferenceReport report;
  const std::vector<glm::vec3> radiance = reference::point_radiance(mesh, sampler, options, points, &report);
  if (!job().is_root()) return;  // distributed: only rank 0 holds every point (docs/distributed.md)
  image::Image out(samples.width, samples.height, 3);
  for (std::size_t k = 0; k < points.size(); ++k)
    for (int c = 0; c < 3; ++c) out.pixels[std::size_t(samples.samples[k].texel) * 3 + std::size_t(c)] = radiance[k][c];
  image::write(output, out);
  if (quiet) return;
  std::fprintf(stderr, "prt reference: %zu texel sample points of a %dx%d lightmap, %d paths each, %d bounce(s), %.2f s, mean relative standard error %.2g -> %s\n",
               points.size(), samples.width, samples.height, options.samples, options.bounces, report.seconds_trace,
               report.mean_relative_standard_error, output.c_str());
}

}  // namespace prt::cli
