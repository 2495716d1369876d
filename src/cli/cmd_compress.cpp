// prt compress: clustered PCA of a transfer file (src/compress) into a .cprt file, with its error in
// transfer space and, under --env/--light, in shaded radiance; overall and per cluster.
#include <algorithm>
#include <chrono>
#include <cstdio>

#include "cli/arguments.h"
#include "cli/commands.h"
#include "cli/lighting_input.h"
#include "cli/output_paths.h"
#include "compress/cprt_file.h"
#include "compress/shaded_compression.h"
#include "core/error.h"

namespace prt::cli {

namespace {

struct CompressCommandOptions {
  std::string transfer_path, output, env, light;
  int clusters = 0, pca = 0, iterations = 20, threads = 0;
  unsigned seed = 1;
  std::string metric = "shaded";
  bool float16 = false, per_cluster = false, quiet = false;
};

// The clusters with the largest relative transfer error, worst first (at most `count`).
void print_worst_clusters(const compress::CompressedTransfer& c, int count) {
  std::vector<int> order(static_cast<std::size_t>(c.clusters));
  for (int k = 0; k < c.clusters; ++k) order[static_cast<std::size_t>(k)] = k;
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return c.per_cluster[static_cast<std::size_t>(a)].transfer_relative() > c.per_cluster[static_cast<std::size_t>(b)].transfer_relative();
  });
  std::vector<std::size_t> sizes(static_cast<std::size_t>(c.clusters), 0);
  for (std::uint32_t k : c.cluster) ++sizes[k];
  std::fprintf(stderr, "  cluster  points  transfer rel.err%s\n", c.has_radiance_error ? "  radiance rel.err" : "");
  for (int i = 0; i < std::min(count, c.clusters); ++i) {
    const int k = order[static_cast<std::size_t>(i)];
    const compress::ErrorSums& s = c.per_cluster[static_cast<std::size_t>(k)];
    std::fprintf(stderr, "  %7d  %6zu  %16.6g", k, sizes[static_cast<std::size_t>(k)], s.transfer_relative());
    if (c.has_radiance_error) std::fprintf(stderr, "  %16.6g", s.radiance_relative());
    std::fprintf(stderr, "\n");
  }
}

// The summary on stderr: sizes, iterations, time, errors.
void report_compression(const compress::CompressedTransfer& c, double seconds, const std::string& output) {
  const std::uint64_t before = compress::uncompressed_bytes(c.source, transfer::Scalar::float32);
  const std::uint64_t after = compress::payload_bytes(c);
  std::fprintf(stderr, "prt compress: %zu %s x %zu values, %d clusters, %d PCA vectors, %d iterations, %.2f s\n",
               c.cluster.size(), c.source.is_texel() ? "texels" : "vertices", c.dimension(), c.clusters, c.pca, c.iterations, seconds);
  std::fprintf(stderr, "  size: %llu -> %llu bytes (%.2f%% of float32)\n", static_cast<unsigned long long>(before),
               static_cast<unsigned long long>(after), 100.0 * static_cast<double>(after) / static_cast<double>(before));
  std::fprintf(stderr, "  transfer rel. error (rms): %.6g\n", c.total.transfer_relative());
  if (c.has_radiance_error)
    std::fprintf(stderr, "  shaded radiance rel. error (rms): %.6g (what the transfer shades: the sky's SH%s)\n",
                 c.total.radiance_relative(), c.bounce ? " and the discs' bounce light" : "");
  std::fprintf(stderr, "  -> %s\n", output.c_str());
}

void run_compress(const CompressCommandOptions& o) {
  if (!o.env.empty() && !o.light.empty()) fail("compress: give at most one of --env ENV and --light LIGHT.json");
  check_outputs({o.output}, {o.transfer_path, o.env, o.light});  // before the work
  const transfer::TransferData transfer = transfer::read_transfer(o.transfer_path);
  compress::CompressionRequest request;
  request.options = {o.clusters, o.pca, o.iterations, o.seed, o.threads};
  request.scalar = o.float16 ? transfer::Scalar::float16 : transfer::Scalar::float32;
  request.shaded_metric = o.metric == "shaded";
  const auto start = std::chrono::steady_clock::now();
  // The lighting as shading splits it: the sun as discs, the rest as the sky's SH.
  const std::string lighting_spec = o.env.empty() ? o.light : o.env;
  light::SceneLighting lighting;
  if (!lighting_spec.empty()) {
    lighting = load_scene_lighting(lighting_spec, static_cast<int>(transfer.header.bands), glm::dvec3(0.0),
                                   LightingArguments{}, o.threads, transfer::is_glossy(transfer.header.kind));
    request.lighting = &lighting;
  }
  const compress::CompressedTransfer c = compress::compress_for_shading(transfer, o.transfer_path, request);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  compress::write_cprt(o.output, c);
  if (o.quiet) return;
  report_compression(c, seconds, o.output);
  if (o.per_cluster) print_worst_clusters(c, c.clusters);
}

}  // namespace

void add_compress_command(CLI::App& app) {
  auto options = std::make_shared<CompressCommandOptions>();
  CLI::App* cmd = app.add_subcommand("compress", "Compress a transfer file with clustered PCA (Sloan et al. 2003) into a .cprt file");
  cmd->add_option("TRANSFER", options->transfer_path, "Transfer file (.prt), diffuse or glossy, per vertex or a lightmap (per texel)")->required();
  cmd->add_option("--clusters", options->clusters, "K: clusters, 1..vertex count")->required();
  cmd->add_option("--pca", options->pca, "N: principal directions per cluster, 1..values per vertex")->required();
  cmd->add_option("--iterations", options->iterations, "Most CPCA rounds (stops earlier when the error stops falling)")
      ->capture_default_str();
  cmd->add_option("--seed", options->seed, "Seed of the initial clusters")->capture_default_str();
  cmd->add_option("--threads", options->threads, "Worker threads (0 = all cores); output does not depend on it")->capture_default_str();
  cmd->add_option("--env", options->env,
                  "Fit to and report the shaded-radiance error under this environment image (split as prt shade does: "
                  "the sun as a disc, the sky as SH)");
  cmd->add_option("--light", options->light, "As --env, for an SH lighting JSON");
  cmd->add_option("--metric", options->metric,
                  "Error CPCA minimises: shaded = outgoing radiance (glossy: through the baked BRDF; with --env/--light: "
                  "averaged over rotations of that lighting), transfer = plain L2 of the values")
      ->check(CLI::IsMember({"shaded", "transfer"}))
      ->capture_default_str();
  cmd->add_flag("--float16", options->float16, "Store means, directions and weights as IEEE float16");
  cmd->add_flag("--per-cluster", options->per_cluster, "Print every cluster's size and error, worst first");
  cmd->add_flag("-q,--quiet", options->quiet, "No summary");
  cmd->add_option("-o,--output", options->output, "Output compressed transfer (.cprt)")->required();
  cmd->callback([options] { run_compress(*options); });
}

}  // namespace prt::cli
