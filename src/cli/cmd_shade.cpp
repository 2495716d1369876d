// prt shade: per-vertex outgoing radiance = transfer . lighting (glossy: toward an eye point), written as a
// colour PLY or a .glb.
#include <algorithm>
#include <cstdio>

#include "brdf/brdf.h"
#include "brdf/projection.h"
#include "cli/arguments.h"
#include "cli/output_paths.h"
#include "cli/commands.h"
#include "cli/lighting_input.h"
#include "compress/cprt_file.h"
#include "compress/open_transfer.h"
#include "core/error.h"
#include "image/image.h"
#include "lightmap/lightmap_shading.h"
#include "mesh/mesh.h"
#include "mesh/writers.h"
#include "shade/glossy.h"
#include "shade/scene_shading.h"
#include "shade/shade.h"
#include "transfer/transfer_file.h"

namespace prt::cli {

namespace {

struct ShadeCommandOptions {
  std::string mesh_path, transfer_path, env, light, rotate, output, eye, brdf;
  int scene = mesh::kDefaultScene;
  LightingArguments lighting;
  shade::DiscShadingOptions discs;
  bool quiet = false;
  bool lightmap = false;  // texel transfer: write the lit lightmap (EXR)
  int threads = 0;
  int bands = 0;  // run-time truncation: shade with the first N lighting bands (0 = all the transfer's)
};

bool has_extension(const std::string& path, const std::string& ext) {
  return path.size() >= ext.size() && path.compare(path.size() - ext.size(), ext.size(), ext) == 0;
}

void run_shade(const ShadeCommandOptions& o) {
  if (o.env.empty() == o.light.empty()) fail("shade: give exactly one of --env ENV and --light LIGHT.json");
  const bool glb = has_extension(o.output, ".glb");
  if (o.lightmap && !has_extension(o.output, ".exr")) fail_file(o.output, "--lightmap output must be .exr (linear radiance)");
  if (!o.lightmap && !glb && !has_extension(o.output, ".ply")) fail_file(o.output, "output must be .ply or .glb");
  check_outputs({o.output}, {o.mesh_path, o.transfer_path, o.env, o.light, o.brdf});
  const glm::dvec3 angles = o.rotate.empty() ? glm::dvec3(0.0) : parse_angles(o.rotate, "--rotate");
  mesh::Mesh mesh = mesh::load_mesh(o.mesh_path, {o.scene, true});
  compress::TransferFile file = compress::open_transfer(o.transfer_path);  // .prt, .cprt or an engine glTF
  if (file.header().mesh_fingerprint == mesh::fingerprint(mesh)) compress::use_baked_albedo(file, &mesh);
  const transfer::TransferData transfer = compress::expand(std::move(file));
  if (transfer.header.is_texel() != o.lightmap)
    fail_file(o.transfer_path, o.lightmap ? "--lightmap needs a lightmap (bake it with prt bake --lightmap WxH)"
                                          : "is a lightmap: shade it with --lightmap -o OUT.exr");
  transfer::check_mesh_match(o.transfer_path, transfer.header, mesh.positions.size(), mesh.indices.size() / 3,
                             mesh::fingerprint(mesh));
  const bool glossy = transfer::is_glossy(transfer.header.kind);
  if (glossy && o.eye.empty()) fail_file(o.transfer_path, "glossy transfer needs --eye X,Y,Z (view-dependent shading)");
  if (!glossy && (!o.eye.empty() || !o.brdf.empty()))
    fail_file(o.transfer_path, std::string("--eye and --brdf apply to glossy transfer; this one is ") +
                                   transfer::kind_name(transfer.header.kind));
  // Projected (and windowed) at the bands it is shaded with: the run-time truncation (shade::shading_bands).
  const light::SceneLighting lighting = load_scene_lighting(o.env.empty() ? o.light : o.env, shade::shading_bands(transfer.header, o.bands),
                                                            angles, o.lighting, o.threads, glossy);
  shade::DiscShadingOptions disc_options = o.discs;
  disc_options.threads = o.threads;
  shade::SplitReport report;
  if (o.lightmap) {
    image::write(o.output, lightmap::shade_lightmap(mesh, transfer, lighting, o.transfer_path, disc_options, &report));
    if (!report.warning.empty()) std::fprintf(stderr, "prt: warning: %s\n", report.warning.c_str());
    return;
  }
  std::vector<glm::vec3> radiance;
  if (glossy) {
    // From --brdf, or the BRDFs recorded at bake time (each vertex's own for --brdf mesh).
    const glm::vec3 eye(parse_triple(o.eye, "--eye", "X,Y,Z (mesh units)"));
    const brdf::VertexBrdfs brdfs = o.brdf.empty() ? shade::baked_brdfs(transfer.header, o.transfer_path)
                                                   : brdf::VertexBrdfs{{brdf::parse_brdf(o.brdf)}, {}};
    radiance = shade::shade_glossy_vertex_brdfs(mesh, transfer, brdfs, lighting, eye, o.transfer_path, disc_options, &report);
  } else {
    radiance = shade::shade_diffuse_split(mesh, transfer, lighting, o.transfer_path, disc_options, &report);
  }
  if (!report.warning.empty()) std::fprintf(stderr, "prt: warning: %s\n", report.warning.c_str());
  if (!o.quiet && (!lighting.discs.empty() || lighting.window.window != sh::Window::none))
    std::fprintf(stderr, "prt shade: %s\n", light::describe_lighting(lighting).c_str());
  if (glb)
    mesh::write_glb(o.output, mesh, radiance);
  else
    mesh::write_ply(o.output, mesh.positions, radiance, mesh.indices);
}

}  // namespace

void add_shade_command(CLI::App& app) {
  auto options = std::make_shared<ShadeCommandOptions>();
  CLI::App* cmd = app.add_subcommand("shade", "Per-vertex outgoing radiance (transfer . lighting) as a colour PLY or .glb (COLOR_0)");
  cmd->add_option("MESH", options->mesh_path, "The mesh the transfer was baked for")->required();
  add_scene_option(cmd, options->scene);
  cmd->add_option("TRANSFER", options->transfer_path, "Transfer file (.prt) or compressed transfer (.cprt)")->required();
  cmd->add_option("--env", options->env, "Environment image (equirect 2:1, cross, or six faces) projected to the transfer's bands");
  cmd->add_option("--light", options->light, "SH lighting JSON written by `prt light`");
  cmd->add_option("--rotate", options->rotate, "YAW,PITCH,ROLL degrees: rotate the lighting by Ry Rx Rz");
  cmd->add_option("--threads", options->threads, "Threads for the projection (0 = all cores)");
  cmd->add_option("--eye", options->eye, "Glossy transfer: X,Y,Z eye point (mesh units); radiance toward it per vertex");
  cmd->add_option("--brdf", options->brdf,
                  "Glossy transfer: BRDF SPEC to shade with (default: the one recorded in the transfer at bake time)");
  cmd->add_option("-o,--output", options->output, "Output .ply (float x,y,z,red,green,blue) or .glb (COLOR_0)")->required();
  cmd->add_option("--bands", options->bands,
                  "Shade with only the first N bands of the lighting (1..the transfer's bands; 0 = all): a cheaper tier of a high-band bake")
      ->capture_default_str();
  add_lighting_options(cmd, options->lighting);
  cmd->add_option("--sun-samples", options->discs.samples, "Stratified shadow rays per vertex and disc (rounded up to a square)")
      ->capture_default_str();
  cmd->add_flag("--lightmap", options->lightmap,
                "TRANSFER is a lightmap (prt bake --lightmap): write the lit lightmap, one linear RGB texel per lightmap texel, as "
                "-o OUT.exr");
  cmd->add_flag("-q,--quiet", options->quiet, "No summary line");
  cmd->callback([options] { run_shade(*options); });
}

}  // namespace prt::cli
