// prt compare-image: differences between two images (temporary; to be merged into `prt compare`).
#include <cstdio>

#include "cli/commands.h"
#include "render/image_compare.h"

namespace prt::cli {

namespace {

struct CompareImageOptions {
  std::string test, reference, heatmap;
};

void run_compare_image(const CompareImageOptions& o) {
  const render::ImageDifference d = render::compare_image_files(o.test, o.reference, o.heatmap);
  std::printf("pixels %dx%d, channels %d, compared %zu, non_finite %zu\n", d.width, d.height, d.channels, d.compared,
              d.non_finite);
  std::printf("rms %.9g\nrel_rms %.9g\nmax %.9g at (%d, %d)\n", d.rms, d.rel_rms, d.max_abs, d.max_x, d.max_y);
}

}  // namespace

void add_compare_image_command(CLI::App& app) {
  auto options = std::make_shared<CompareImageOptions>();
  CLI::App* cmd = app.add_subcommand("compare-image", "Compare two images (e.g. EXR renders): rms, rel_rms, max");
  cmd->add_option("TEST", options->test, "Image to test")->required();
  cmd->add_option("REFERENCE", options->reference, "Reference image (rel_rms is relative to its rms)")->required();
  cmd->add_option("--heatmap", options->heatmap, "Write a PNG of max-channel |TEST - REFERENCE| (black-red-yellow-white)");
  cmd->callback([options] { run_compare_image(*options); });
}

}  // namespace prt::cli
