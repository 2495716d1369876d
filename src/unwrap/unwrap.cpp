#include "unwrap/unwrap.h"

#include <algorithm>
#include <chrono>

#include "core/error.h"
#include "core/parallel.h"
#include "core/stopwatch.h"
#include "unwrap/charts.h"
#include "unwrap/embedding.h"
#include "unwrap/lscm.h"
#include "unwrap/pack.h"

namespace prt::unwrap {

namespace {

struct Flattened {
  std::vector<FlatChart> charts;
  std::size_t cut = 0, planar = 0;
};

// The two halves of `triangles` about the median centroid along the axis of their largest extent.
std::pair<std::vector<std::uint32_t>, std::vector<std::uint32_t>> halves(const mesh::Mesh& mesh, std::vector<std::uint32_t> triangles) {
  std::vector<glm::dvec3> centroid(triangles.size());
  glm::dvec3 lo(1e300), hi(-1e300);
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    const std::size_t t = triangles[i];
    centroid[i] = (glm::dvec3(mesh.positions[mesh.indices[3 * t]]) + glm::dvec3(mesh.positions[mesh.indices[3 * t + 1]]) +
                   glm::dvec3(mesh.positions[mesh.indices[3 * t + 2]])) / 3.0;
    lo = glm::min(lo, centroid[i]);
    hi = glm::max(hi, centroid[i]);
  }
  const glm::dvec3 extent = hi - lo;
  const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
  std::vector<std::size_t> order(triangles.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return centroid[a][axis] < centroid[b][axis] || (centroid[a][axis] == centroid[b][axis] && triangles[a] < triangles[b]);
  });
  std::pair<std::vector<std::uint32_t>, std::vector<std::uint32_t>> out;
  for (std::size_t i = 0; i < order.size(); ++i) (i < order.size() / 2 ? out.first : out.second).push_back(triangles[order[i]]);
  return out;
}

// Flattens one grown chart, cutting pieces until every map is one-to-one (depth first, first half first).
void flatten(const mesh::Mesh& mesh, const Surface& surface, const std::vector<std::uint32_t>& triangles, Flattened& out) {
  FlatChart chart{triangles, {}};
  if (triangles.size() == 1) {
    planar_chart(mesh, chart);
    out.charts.push_back(std::move(chart));
    return;
  }
  if (lscm_chart(mesh, surface, chart) && is_embedding(mesh, surface, chart)) {
    out.charts.push_back(std::move(chart));
    return;
  }
  if (triangles.size() <= kPlanarPiece) {
    planar_chart(mesh, chart);
    if (is_embedding(mesh, surface, chart)) {
      ++out.planar;
      out.charts.push_back(std::move(chart));
      return;
    }
  }
  ++out.cut;
  const auto parts = halves(mesh, triangles);
  for (const std::vector<std::uint32_t>* part : {&parts.first, &parts.second})
    for (const std::vector<std::uint32_t>& piece : connected_pieces(surface, *part)) flatten(mesh, surface, piece, out);
}

}  // namespace

void check_options(const UnwrapOptions& options) {
  if (options.width < 1 || options.height < 1 || options.width > 16384 || options.height > 16384)
    fail_option("size", " " + std::to_string(options.width) + "x" + std::to_string(options.height) + ": each side must be 1..16384 texels");
  if (options.padding < 0 || options.padding > 64) fail_option("padding", " " + std::to_string(options.padding) + " is out of range 0..64");
  check_chart_options(ChartOptions{options.chart_angle});
}

std::vector<glm::vec2> unwrap(const mesh::Mesh& mesh, const UnwrapOptions& options, UnwrapReport* report) {
  const auto start = std::chrono::steady_clock::now();
  check_options(options);
  const Surface surface = build_surface(mesh);
  const std::vector<std::vector<std::uint32_t>> grown = make_charts(mesh, surface, ChartOptions{options.chart_angle});
  std::vector<Flattened> flat(grown.size());
  parallel_for(grown.size(), 4, options.threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t c = begin; c < end; ++c) flatten(mesh, surface, grown[c], flat[c]);
  });
  UnwrapReport rep;
  rep.grown_charts = grown.size();
  std::vector<FlatChart> charts;
  for (Flattened& f : flat) {
    rep.cut_charts += f.cut;
    rep.planar_pieces += f.planar;
    for (FlatChart& chart : f.charts) charts.push_back(std::move(chart));
  }
  rep.charts = charts.size();
  std::vector<glm::vec2> uv(mesh.indices.size());
  PackResult packed;
  try {
    packed = pack_charts(charts, PackOptions{options.width, options.height, options.padding}, uv);
  } catch (const OptionError&) {
    throw;
  } catch (const Error& e) {
    if (options.mesh_path.empty()) throw;
    fail_file(options.mesh_path, e.what());
  }
  rep.texels_per_unit = packed.texels_per_unit;
  rep.fill = packed.fill;
  rep.seconds = seconds_since(start);
  if (report) *report = rep;
  return uv;
}

}  // namespace prt::unwrap
