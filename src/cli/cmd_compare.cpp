// prt compare: error statistics of a result A against a reference B, either two per-vertex radiance
// PLYs or two images (image/compare.h defines every figure).
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>

#include "cli/commands.h"
#include "cli/output_paths.h"
#include "core/error.h"
#include "core/text.h"
#include "image/compare.h"
#include "image/image.h"
#include "mesh/writers.h"

namespace prt::cli {

namespace {

struct CompareCommandOptions {
  std::string a, b, heatmap;
};

bool is_ply(const std::string& path) {
  return lower_extension(path) == ".ply";
}

// Blue -> cyan -> green -> yellow -> red over t in [0, 1].
glm::vec3 heat_colour(float t) {
  t = std::clamp(t, 0.0f, 1.0f) * 4.0f;
  if (t < 1) return {0, t, 1};
  if (t < 2) return {0, 1, 2 - t};
  if (t < 3) return {t - 2, 1, 0};
  return {1, 4 - t, 0};
}

// Nothing finite to compare: an rms of 0 would read as a perfect match.
void require_finite_values(const image::Difference& d) {
  if (d.compared == 0 && d.non_finite > 0)
    fail("nothing to compare: all " + std::to_string(d.non_finite) + " values are NaN or infinite in A or B");
}

void print_line(const image::Difference& d, const char* count_name, std::size_t count) {
  require_finite_values(d);
  std::printf("rms=%.6g rel_rms=%.6g max_abs=%.6g max_rel=%.6g %s=%zu", d.rms, d.rel_rms, d.max_abs, d.max_rel,
              count_name, count);
  if (d.non_finite > 0) std::printf(" non_finite=%zu", d.non_finite);
  std::printf("\n");
}

void compare_plys(const CompareCommandOptions& o) {
  check_outputs({o.heatmap}, {o.a, o.b});
  if (!o.heatmap.empty() && !is_ply(o.heatmap)) fail_file(o.heatmap, "the heatmap of two PLYs is a .ply");
  const mesh::ColourPly a = mesh::read_ply_colours(o.a);
  const mesh::ColourPly b = mesh::read_ply_colours(o.b);
  if (a.colours.size() != b.colours.size())
    fail(o.a + " has " + std::to_string(a.colours.size()) + " vertices but " + o.b + " has " +
         std::to_string(b.colours.size()));
  if (a.colours.empty()) fail_file(o.a, "no vertices to compare");
  static_assert(sizeof(glm::vec3) == 3 * sizeof(float), "colours are read as 3 contiguous floats per vertex");
  const image::Difference d = image::compare_values(&a.colours[0].x, &b.colours[0].x, 3 * a.colours.size());
  require_finite_values(d);
  if (!o.heatmap.empty()) {
    std::vector<glm::vec3> heat(a.colours.size());
    for (std::size_t v = 0; v < a.colours.size(); ++v) {
      double worst = 0.0;
      for (int c = 0; c < 3; ++c)
        worst = std::max(worst, image::relative_error(a.colours[v][c], b.colours[v][c], d.reference_rms));
      heat[v] = heat_colour(static_cast<float>(worst / 0.1));
    }
    mesh::write_ply(o.heatmap, b.positions, heat, b.indices);
  }
  print_line(d, "vertices", a.colours.size());
}

void compare_images(const CompareCommandOptions& o) {
  if (!o.heatmap.empty() && !image::is_display_format(o.heatmap))
    fail_file(o.heatmap, "the heatmap of two images is an 8-bit image (.png)");
  check_outputs({o.heatmap}, {o.a, o.b});
  const image::ImageDifference d = image::compare_image_files(o.a, o.b, o.heatmap);
  print_line(d.values, "pixels", static_cast<std::size_t>(d.width) * static_cast<std::size_t>(d.height));
}

void run_compare(const CompareCommandOptions& o) {
  const bool a_ply = is_ply(o.a), b_ply = is_ply(o.b);
  if (a_ply != b_ply)
    fail((a_ply ? o.a : o.b) + " is a per-vertex PLY but " + (a_ply ? o.b : o.a) +
         " is an image: compare two PLYs or two images");
  if (a_ply) compare_plys(o);
  else compare_images(o);
}

}  // namespace

void add_compare_command(CLI::App& app) {
  auto options = std::make_shared<CompareCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "compare",
      "Compare A with the reference B, two per-vertex radiance PLYs or two images (.exr or any image prt reads); "
      "prints one line: rms, rel_rms (= rms / rms of B), max_abs, max_rel (|A-B| / max(|B|, 1% of B's rms)), "
      "vertices or pixels");
  cmd->add_option("A", options->a, "Result to judge: colour PLY (e.g. `prt shade`) or image (e.g. `prt render`)")
      ->required();
  cmd->add_option("B", options->b, "Reference of the same kind (e.g. `prt reference`, `prt reference --image`)")
      ->required();
  cmd->add_option("--heatmap", options->heatmap,
                  "PLYs: write B's mesh (.ply) coloured by each vertex's max_rel (blue 0 .. red >= 10%); images: "
                  "write a PNG of each pixel's max_rel (black 0, red, yellow, white >= 10%; blue where not finite)");
  cmd->callback([options] { run_compare(*options); });
}

}  // namespace prt::cli
