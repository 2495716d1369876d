// prt brdf: projects a cosine-weighted BRDF into its SH matrix B (src/brdf) and writes it as .json or
// .bin, optionally with a PNG plot of the reconstructed lobes.
#include <chrono>
#include <memory>
#include <cstdio>
#include <sstream>

#include "brdf/brdf.h"
#include "brdf/brdf_file.h"
#include "brdf/lobe_plot.h"
#include "brdf/projection.h"
#include "cli/commands.h"
#include "cli/output_paths.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "image/image.h"
#include "sh/basis.h"

namespace prt::cli {

namespace {

struct BrdfCommandOptions {
  std::string spec, output, preview;
  std::string angles = "0,30,60,80";
  int bands = 5;
  bool quiet = false;
};

std::vector<double> parse_angles_list(const std::string& text) {
  std::vector<double> out;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (item.empty() || *end != '\0' || !(v >= 0.0 && v < 90.0))
      fail("--angles: expected incident angles in degrees in [0, 90) separated by commas, got '" + text + "'");
    out.push_back(v);
  }
  if (out.empty() || out.size() > 6) fail("--angles: expected 1 to 6 angles, got '" + text + "'");
  return out;
}

void run_brdf(const BrdfCommandOptions& o) {
  if (o.bands < 1 || o.bands > sh::kMaxBands)
    fail("--bands " + std::to_string(o.bands) + " is out of range 1.." + std::to_string(sh::kMaxBands));
  const brdf::Brdf brdf = brdf::parse_brdf(o.spec);
  const std::vector<double> angles = parse_angles_list(o.angles);
  check_outputs({o.output, o.preview}, {o.spec});
  if (!o.preview.empty() && !image::is_display_format(o.preview))
    fail_file(o.preview, "--preview must be a .png (or another 8-bit format)");
  const auto start = std::chrono::steady_clock::now();
  const brdf::BrdfMatrix matrix = brdf::project(brdf, o.bands);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // Both outputs are committed together: a failing preview leaves no matrix file behind.
  AtomicFile matrix_file(o.output);
  write_staged(matrix_file, [&](const std::string& path) { brdf::write_brdf_matrix(path, matrix); });
  std::unique_ptr<AtomicFile> preview_file;
  if (!o.preview.empty()) {
    preview_file = std::make_unique<AtomicFile>(o.preview);
    const image::Image plot = brdf::plot_lobes(brdf, matrix, angles);
    write_staged(*preview_file, [&](const std::string& path) { image::write_file_at(path, plot, o.preview); });
  }
  matrix_file.commit();
  if (preview_file) preview_file->commit();
  if (!o.quiet) {
    const double error = brdf::reconstruction_error(brdf, matrix);
    std::fprintf(stderr,
                 "prt brdf: %s, %d bands, %d channel(s), projected in %.3f s; reconstruction error %.4g "
                 "(relative L2 over both hemispheres) -> %s\n",
                 matrix.spec.c_str(), matrix.bands, matrix.channels, seconds, error, o.output.c_str());
  }
}

}  // namespace

void add_brdf_command(CLI::App& app) {
  auto options = std::make_shared<BrdfCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "brdf", "Project a cosine-weighted BRDF into its SH matrix B (O = B T in the local frame) as .json or .bin");
  cmd->add_option("SPEC", options->spec,
                  "BRDF: e.g. lambert:albedo=0.8, phong:exponent=32,ks=0.5,kd=0.3, blinn:exponent=64, "
                  "ggx:roughness=0.3,f0=0.04,albedo=0.5, gltf:basecolor=R/G/B,metallic=M,roughness=R, "
                  "lobes joined by '+', or a .json material file")
      ->required();
  cmd->add_option("--bands", options->bands, "SH bands (1..32): B is bands^2 x bands^2")->capture_default_str();
  cmd->add_option("-o,--output", options->output, "Output BRDF matrix (.json or .bin)")->required();
  cmd->add_option("--preview", options->preview, "Also plot true and reconstructed lobes in the plane of incidence (.png)");
  cmd->add_option("--angles", options->angles, "Incident angles of the preview, degrees")->capture_default_str();
  cmd->add_flag("-q,--quiet", options->quiet, "No summary line");
  cmd->callback([options] { run_brdf(*options); });
}

}  // namespace prt::cli
