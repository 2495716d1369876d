// prt unwrap: generates lightmap UVs (src/unwrap) and writes the mesh with its materials and them as TEXCOORD_1 (.glb).
#include <cstdio>
#include <memory>

#include "cli/arguments.h"
#include "cli/commands.h"
#include "cli/output_paths.h"
#include "core/error.h"
#include "lightmap/texel_bake.h"
#include "mesh/engine_gltf.h"
#include "mesh/mesh.h"
#include "unwrap/unwrap.h"

namespace prt::cli {

namespace {

struct UnwrapCommandOptions {
  std::string mesh_path;
  int scene = mesh::kDefaultScene;
  std::string output;
  std::string size = "1024";
  int padding = 2;
  double angle = 60.0;
  int threads = 0;
  bool quiet = false;
};

void run_unwrap(const UnwrapCommandOptions& o) {
  unwrap::UnwrapOptions options;
  lightmap::parse_lightmap_size(o.size, options.width, options.height);
  options.padding = o.padding;
  options.chart_angle = o.angle;
  options.threads = o.threads;
  options.mesh_path = o.mesh_path;
  unwrap::check_options(options);
  check_outputs({o.output}, {o.mesh_path});
  mesh::Mesh mesh = mesh::load_mesh(o.mesh_path, mesh::LoadOptions{o.scene, o.quiet});
  unwrap::UnwrapReport report;
  mesh.lightmap_uv = unwrap::unwrap(mesh, options, &report);
  mesh.lightmap_uv_set = 1;
  // The source with the generated UVs as TEXCOORD_1 (docs/formats.md, "Unwrapped mesh").
  mesh::EngineExtras extras;
  extras.lightmap_set = 1;
  extras.corner_uvs = true;
  mesh::write_engine_glb(o.output, o.mesh_path, mesh, extras);
  if (o.quiet) return;
  std::fprintf(stderr,
               "prt unwrap: %zu triangles, %zu charts (%zu grown, %zu cut, %zu planar), %dx%d texels, padding %d, "
               "%.4g texels per unit, %.1f%% filled, %.2f s -> %s\n",
               mesh.triangle_count(), report.charts, report.grown_charts, report.cut_charts, report.planar_pieces, options.width,
               options.height, options.padding, report.texels_per_unit, 100.0 * report.fill, report.seconds, o.output.c_str());
}

}  // namespace

void add_unwrap_command(CLI::App& app) {
  auto options = std::make_shared<UnwrapCommandOptions>();
  CLI::App* cmd = app.add_subcommand("unwrap", "Generate lightmap UVs (charts, conformal maps, packing) and write the mesh as .glb with them as TEXCOORD_1");
  cmd->add_option("MESH", options->mesh_path, "Input mesh (.obj, .ply, .gltf, .glb)")->required();
  add_scene_option(cmd, options->scene);
  cmd->add_option("-o,--output", options->output, "Output mesh (.glb): the mesh as loaded with its materials, the lightmap UVs as TEXCOORD_1")->required();
  cmd->add_option("--size", options->size, "WxH or SIZE: the lightmap the charts are packed for, in texels")->capture_default_str();
  cmd->add_option("--padding", options->padding, "Empty texels around every chart (0..64; two charts are at least twice that apart)")
      ->capture_default_str();
  cmd->add_option("--chart-angle", options->angle, "Chart cone: largest angle (degrees, (0, 89]) between a chart's face normals and its seed's")
      ->capture_default_str();
  cmd->add_option("--threads", options->threads, "Worker threads (0 = all cores); the UVs do not depend on it")->capture_default_str();
  cmd->add_flag("-q,--quiet", options->quiet, "No summary");
  cmd->callback([options] { run_unwrap(*options); });
}

}  // namespace prt::cli
