#include "unwrap/embedding.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include <glm/geometric.hpp>

namespace prt::unwrap {

namespace {

double orient(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

struct Segment {
  glm::dvec2 a, b;
  std::uint32_t va, vb;  // welded vertices
};

bool segments_meet(const Segment& s, const Segment& t) {
  if (s.va == t.va || s.va == t.vb || s.vb == t.va || s.vb == t.vb) return false;  // neighbours on the border
  const double d1 = orient(s.a, s.b, t.a), d2 = orient(s.a, s.b, t.b), d3 = orient(t.a, t.b, s.a), d4 = orient(t.a, t.b, s.b);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return true;
  auto on = [](const glm::dvec2& p, const glm::dvec2& q, const glm::dvec2& r) {  // r on segment pq, given collinear
    return std::min(p.x, q.x) <= r.x && r.x <= std::max(p.x, q.x) && std::min(p.y, q.y) <= r.y && r.y <= std::max(p.y, q.y);
  };
  return (d1 == 0 && on(s.a, s.b, t.a)) || (d2 == 0 && on(s.a, s.b, t.b)) || (d3 == 0 && on(t.a, t.b, s.a)) ||
         (d4 == 0 && on(t.a, t.b, s.b));
}

std::vector<Segment> border_segments(const Surface& surface, const FlatChart& chart) {
  std::vector<std::uint32_t> sorted = chart.triangles;
  std::sort(sorted.begin(), sorted.end());
  std::vector<Segment> out;
  for (std::size_t i = 0; i < chart.triangles.size(); ++i)
    for (std::size_t k = 0; k < 3; ++k) {
      const std::size_t corner = 3 * std::size_t(chart.triangles[i]) + k, next = corner - k + (k + 1) % 3;
      const std::uint32_t n = surface.neighbour[corner];
      if (n != kNoNeighbour && std::binary_search(sorted.begin(), sorted.end(), n)) continue;
      out.push_back({chart.corner_uv[3 * i + k], chart.corner_uv[3 * i + (k + 1) % 3], surface.welded[corner], surface.welded[next]});
    }
  return out;
}

}  // namespace

std::size_t count_folds(const mesh::Mesh& mesh, const FlatChart& chart) {
  std::size_t folds = 0;
  for (std::size_t i = 0; i < chart.triangles.size(); ++i) {
    const std::size_t t = chart.triangles[i];
    const glm::dvec3 a(mesh.positions[mesh.indices[3 * t]]), b(mesh.positions[mesh.indices[3 * t + 1]]), c(mesh.positions[mesh.indices[3 * t + 2]]);
    const double area = glm::length(glm::cross(b - a, c - a));
    const double uv_area = orient(chart.corner_uv[3 * i], chart.corner_uv[3 * i + 1], chart.corner_uv[3 * i + 2]);
    if (!(uv_area > kMinAreaRatio * area)) ++folds;
  }
  return folds;
}

bool border_crosses(const Surface& surface, const FlatChart& chart) {
  const std::vector<Segment> segments = border_segments(surface, chart);
  if (segments.size() < 4) return false;
  glm::dvec2 lo(1e300), hi(-1e300);
  double length = 0.0;
  for (const Segment& s : segments) {
    lo = glm::min(lo, glm::min(s.a, s.b));
    hi = glm::max(hi, glm::max(s.a, s.b));
    length += glm::length(s.b - s.a);
  }
  const double cell = std::max(length / double(segments.size()), 1e-300);
  const double cap = 2.0 * std::sqrt(double(segments.size())) + 1.0;  // bounds the cells a long edge spans
  const auto cells_x = std::int64_t(std::min(cap, std::floor((hi.x - lo.x) / cell) + 1.0));
  const auto cells_y = std::int64_t(std::min(cap, std::floor((hi.y - lo.y) / cell) + 1.0));
  const glm::dvec2 size((hi.x - lo.x) / double(cells_x) + 1e-300, (hi.y - lo.y) / double(cells_y) + 1e-300);
  std::unordered_map<std::int64_t, std::vector<std::uint32_t>> grid;
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const glm::dvec2 a = (glm::min(segments[i].a, segments[i].b) - lo) / size, b = (glm::max(segments[i].a, segments[i].b) - lo) / size;
    const std::int64_t x0 = std::clamp(std::int64_t(a.x), std::int64_t(0), cells_x - 1), x1 = std::clamp(std::int64_t(b.x), std::int64_t(0), cells_x - 1);
    const std::int64_t y0 = std::clamp(std::int64_t(a.y), std::int64_t(0), cells_y - 1), y1 = std::clamp(std::int64_t(b.y), std::int64_t(0), cells_y - 1);
    for (std::int64_t y = y0; y <= y1; ++y)
      for (std::int64_t x = x0; x <= x1; ++x) {
        std::vector<std::uint32_t>& bucket = grid[y * cells_x + x];
        for (std::uint32_t j : bucket)
          if (segments_meet(segments[i], segments[j])) return true;
        bucket.push_back(std::uint32_t(i));
      }
  }
  return false;
}

bool wraps_around_vertex(const Surface& surface, const FlatChart& chart) {
  std::unordered_map<std::uint32_t, double> angle;
  for (std::size_t i = 0; i < chart.triangles.size(); ++i)
    for (std::size_t k = 0; k < 3; ++k) {
      const glm::dvec2 a = chart.corner_uv[3 * i + k], b = chart.corner_uv[3 * i + (k + 1) % 3], c = chart.corner_uv[3 * i + (k + 2) % 3];
      const glm::dvec2 u = b - a, v = c - a;
      angle[surface.welded[3 * std::size_t(chart.triangles[i]) + k]] += std::atan2(std::abs(u.x * v.y - u.y * v.x), glm::dot(u, v));
    }
  for (const Segment& s : border_segments(surface, chart))
    if (angle[s.va] >= 2.0 * 3.14159265358979323846 - kAngleSlack) return true;
  return false;
}

bool is_embedding(const mesh::Mesh& mesh, const Surface& surface, const FlatChart& chart) {
  return count_folds(mesh, chart) == 0 && !border_crosses(surface, chart) && !wraps_around_vertex(surface, chart);
}

}  // namespace prt::unwrap
