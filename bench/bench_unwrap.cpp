// bench_unwrap: lightmap UV generation (src/unwrap) of a real 100k-triangle mesh against the issue's
// target (issue 35: at most 10 s on 2 cores), with the charting stage alone as the in-run baseline.
//
// Mesh: 2CylinderEngine (glTF sample model from Debian's assimp-testmodels, 110,336 triangles after
// the loader drops degenerate ones, 82 nodes), or the file given. Each configuration runs `--repeats`
// times back to back; the best and the spread (max / best) are printed, since the machine is shared.
// Usage: bench_unwrap [--mesh PATH] [--size N] [--repeats R]
// A timed program, not Google Benchmark.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "core/stopwatch.h"
#include "mesh/mesh.h"
#include "unwrap/charts.h"
#include "unwrap/unwrap.h"

using namespace prt;

namespace {

struct Timing {
  double best = 1e300, worst = 0.0;
  void add(double s) { best = std::min(best, s), worst = std::max(worst, s); }
};

}  // namespace

int main(int argc, char** argv) {
  std::string path = "/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb";
  int size = 1024, repeats = 5;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--mesh")) path = argv[i + 1];
    else if (!std::strcmp(argv[i], "--size")) size = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--repeats")) repeats = std::max(1, std::atoi(argv[i + 1]));
  }
  const mesh::Mesh m = mesh::load_mesh(path, nullptr, true);
  std::printf("%s: %zu triangles, lightmap %dx%d, %d repeats\n", path.c_str(), m.triangle_count(), size, size, repeats);
  Timing charts;
  for (int r = 0; r < repeats; ++r) {
    const auto start = std::chrono::steady_clock::now();
    const unwrap::Surface surface = unwrap::build_surface(m);
    const auto grown = unwrap::make_charts(m, surface, unwrap::ChartOptions{});
    charts.add(seconds_since(start));
    if (grown.empty()) return 1;
  }
  std::printf("  charting alone (baseline): best %.3f s, spread %.2f\n", charts.best, charts.worst / charts.best);
  for (int threads : {1, 2}) {
    Timing total;
    unwrap::UnwrapReport report;
    for (int r = 0; r < repeats; ++r) {
      const auto start = std::chrono::steady_clock::now();
      const std::vector<glm::vec2> uv = unwrap::unwrap(m, unwrap::UnwrapOptions{size, size, 2, 60.0, threads, ""}, &report);
      total.add(seconds_since(start));
      if (uv.size() != m.indices.size()) return 1;
    }
    std::printf("  unwrap, %d thread(s): best %.3f s, spread %.2f, %.1f x charting; %zu charts, %.1f%% filled; target <= 10 s: %s\n",
                threads, total.best, total.worst / total.best, total.best / charts.best, report.charts, 100.0 * report.fill,
                total.best <= 10.0 ? "met" : "MISSED");
  }
  return 0;
}
