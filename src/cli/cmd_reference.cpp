// prt reference: the path-traced ground truth of the per-vertex outgoing radiance (src/reference).
#include <algorithm>
#include <cstdio>
#include <memory>

#include "cli/arguments.h"
#include "cli/commands.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "light/environment.h"
#include "mesh/mesh.h"
#include "mesh/writers.h"
#include "reference/reference.h"
#include "sh/basis.h"

namespace prt::cli {

namespace {

struct ReferenceCommandOptions {
  std::string mesh_path, env, output, albedo;
  int bounces = 0;
  int samples = reference::kDefaultSamples;
  int band_limit = 0;
  unsigned seed = 1;
  int threads = 0;
  bool quiet = false;
};

bool ends_with(const std::string& text, const std::string& suffix) {
  return text.size() >= suffix.size() && text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

void run_reference(const ReferenceCommandOptions& o, bool band_limit_given) {
  reference::ReferenceOptions options;
  options.bounces = o.bounces;
  options.samples = o.samples;
  options.seed = o.seed;
  options.threads = o.threads;
  options.progress = want_progress(o.quiet);
  if (!o.albedo.empty()) options.albedo = glm::vec3(parse_triple(o.albedo, "--albedo", "R,G,B in [0,1]"));
  reference::check_options(options);
  if (band_limit_given && (o.band_limit < 1 || o.band_limit > sh::kMaxBands))
    fail("--band-limit: expected a band count in 1.." + std::to_string(sh::kMaxBands) + ", got " +
         std::to_string(o.band_limit));
  if (!ends_with(o.output, ".ply")) fail_file(o.output, "output must be .ply");
  { AtomicFile probe(o.output); }  // check the output folder before tracing for minutes

  const mesh::Mesh mesh = mesh::load_mesh(o.mesh_path, nullptr, o.quiet);
  light::Environment environment = light::load_environment(o.env);
  if (band_limit_given) environment = reference::band_limited_environment(environment, o.band_limit, o.threads);
  const reference::EnvironmentSampler sampler(std::move(environment));

  reference::ReferenceReport report;
  const std::vector<glm::vec3> radiance = reference::vertex_radiance(mesh, sampler, options, &report);
  mesh::write_ply(o.output, mesh.positions, radiance, mesh.indices);

  if (!o.quiet) {
    const double seconds = std::max(1e-9, report.seconds_trace);
    std::fprintf(stderr,
                 "prt reference: %zu vertices, %d paths each, %d bounce(s), %llu rays in %.2f s (%.3g Mpaths/s, "
                 "%.3g Mrays/s), mean relative standard error %.2g -> %s\n",
                 mesh.positions.size(), options.samples, options.bounces,
                 static_cast<unsigned long long>(report.rays), seconds, report.paths / 1e6 / seconds,
                 report.rays / 1e6 / seconds, report.mean_relative_standard_error, o.output.c_str());
  }
}

}  // namespace

void add_reference_command(CLI::App& app) {
  auto options = std::make_shared<ReferenceCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "reference", "Path-traced ground truth: per-vertex outgoing radiance under an environment, as a colour PLY");
  cmd->add_option("MESH", options->mesh_path, "Input mesh (.obj, .ply, .gltf, .glb)")->required();
  cmd->add_option("--env", options->env, "Environment image (equirect 2:1, cross, or six faces)")->required();
  cmd->add_option("--bounces", options->bounces,
                  "Interreflection bounces (0 = direct light with visibility, as --transfer shadowed)")
      ->capture_default_str();
  cmd->add_option("--samples", options->samples, "Paths per vertex")->capture_default_str();
  cmd->add_option("--albedo", options->albedo, "R,G,B linear albedo for meshes without colours (default 0.8,0.8,0.8)");
  CLI::Option* band_limit = cmd->add_option(
      "--band-limit", options->band_limit,
      "Replace the environment by its reconstruction from its first N SH bands (signed), to compare with a bake of N bands");
  cmd->add_option("--seed", options->seed, "Seed of the per-vertex random streams")->capture_default_str();
  cmd->add_option("--threads", options->threads, "Worker threads (0 = all cores); output does not depend on it")
      ->capture_default_str();
  cmd->add_flag("-q,--quiet", options->quiet, "No progress bar or summary");
  cmd->add_option("-o,--output", options->output, "Output .ply (float x,y,z,red,green,blue, faces)")->required();
  cmd->callback([options, band_limit] { run_reference(*options, band_limit->count() > 0); });
}

}  // namespace prt::cli
