#include "unwrap/charts.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <deque>
#include <numeric>
#include <sstream>

#include <glm/geometric.hpp>

#include "core/error.h"

namespace prt::unwrap {

namespace {

// Welded vertex ids: vertices sorted by their position's float bits (ties by index), equal bits share
// the id of the first; ids numbered in order of the lowest vertex index using them.
std::vector<std::uint32_t> weld_positions(const std::vector<glm::vec3>& positions) {
  struct Key {
    std::uint32_t bits[3];
    std::uint32_t index;
  };
  std::vector<Key> keys(positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i) {
    glm::vec3 p = positions[i] + glm::vec3(0.0f);  // -0 and +0 weld
    std::memcpy(keys[i].bits, &p, sizeof keys[i].bits);
    keys[i].index = std::uint32_t(i);
  }
  std::sort(keys.begin(), keys.end(), [](const Key& a, const Key& b) {
    return std::lexicographical_compare(a.bits, a.bits + 3, b.bits, b.bits + 3) ||
           (std::equal(a.bits, a.bits + 3, b.bits) && a.index < b.index);
  });
  std::vector<std::uint32_t> first(positions.size());
  for (std::size_t i = 0; i < keys.size(); ++i)
    first[keys[i].index] = (i > 0 && std::equal(keys[i].bits, keys[i].bits + 3, keys[i - 1].bits)) ? first[keys[i - 1].index]
                                                                                                   : keys[i].index;
  std::vector<std::uint32_t> id(positions.size(), kNoNeighbour);
  std::uint32_t next = 0;
  for (std::size_t i = 0; i < positions.size(); ++i) {
    if (id[first[i]] == kNoNeighbour) id[first[i]] = next++;
    id[i] = id[first[i]];
  }
  return id;
}

bool same_normal(const mesh::Mesh& mesh, std::uint32_t a, std::uint32_t b) {
  return a == b || double(glm::dot(mesh.normals[a], mesh.normals[b])) >= kSmoothNormalDot;
}

}  // namespace

glm::dvec3 face_normal(const mesh::Mesh& mesh, std::size_t t) {
  const glm::dvec3 a(mesh.positions[mesh.indices[3 * t]]), b(mesh.positions[mesh.indices[3 * t + 1]]),
      c(mesh.positions[mesh.indices[3 * t + 2]]);
  const glm::dvec3 n = glm::cross(b - a, c - a);
  const double length = glm::length(n);
  return length > 0.0 ? n / length : glm::dvec3(0.0, 1.0, 0.0);
}

Surface build_surface(const mesh::Mesh& mesh) {
  if (mesh.normals.size() != mesh.positions.size()) fail("unwrap: the mesh needs one normal per vertex");
  const std::vector<std::uint32_t> weld = weld_positions(mesh.positions);
  Surface s;
  const std::size_t corners = mesh.indices.size();
  s.welded.resize(corners);
  for (std::size_t c = 0; c < corners; ++c) s.welded[c] = weld[mesh.indices[c]];
  s.welded_count = weld.empty() ? 0 : *std::max_element(weld.begin(), weld.end()) + 1;
  // Directed edges (from, to, corner), sorted by undirected key: equal keys are the triangles of one edge.
  struct Edge {
    std::uint64_t key;
    std::uint32_t corner;
  };
  std::vector<Edge> edges(corners);
  for (std::size_t c = 0; c < corners; ++c) {
    const std::uint32_t a = s.welded[c], b = s.welded[c - c % 3 + (c + 1) % 3];
    edges[c] = {(std::uint64_t(std::min(a, b)) << 32) | std::max(a, b), std::uint32_t(c)};
  }
  std::sort(edges.begin(), edges.end(), [](const Edge& x, const Edge& y) { return x.key < y.key || (x.key == y.key && x.corner < y.corner); });
  s.neighbour.assign(corners, kNoNeighbour);
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j].key == edges[i].key) ++j;
    if (j - i == 2) {
      const std::uint32_t c0 = edges[i].corner, c1 = edges[i + 1].corner;
      const std::uint32_t n0 = c0 - c0 % 3 + (c0 + 1) % 3, n1 = c1 - c1 % 3 + (c1 + 1) % 3;
      // Opposite directions: c0's start is c1's end; and the same normals at both ends.
      const bool opposite = s.welded[c0] == s.welded[n1] && s.welded[n0] == s.welded[c1];
      if (opposite && c0 / 3 != c1 / 3 && same_normal(mesh, mesh.indices[c0], mesh.indices[n1]) &&
          same_normal(mesh, mesh.indices[n0], mesh.indices[c1])) {
        s.neighbour[c0] = c1 / 3;
        s.neighbour[c1] = c0 / 3;
      }
    }
    i = j;
  }
  return s;
}

void check_chart_options(const ChartOptions& options) {
  if (!(options.chart_angle > 0.0 && options.chart_angle <= 89.0)) {
    std::ostringstream text;
    text << " " << options.chart_angle << " is out of range (0, 89] degrees";
    fail_option("chart_angle", text.str());
  }
}

std::vector<std::vector<std::uint32_t>> make_charts(const mesh::Mesh& mesh, const Surface& surface, const ChartOptions& options) {
  check_chart_options(options);
  const double min_dot = std::cos(options.chart_angle * 3.14159265358979323846 / 180.0);
  const std::size_t triangles = mesh.triangle_count();
  std::vector<glm::dvec3> normal(triangles);
  for (std::size_t t = 0; t < triangles; ++t) normal[t] = face_normal(mesh, t);
  std::vector<std::uint32_t> chart_of(triangles, kNoNeighbour);
  std::vector<std::vector<std::uint32_t>> charts;
  for (std::size_t seed = 0; seed < triangles; ++seed) {
    if (chart_of[seed] != kNoNeighbour) continue;
    const std::uint32_t id = std::uint32_t(charts.size());
    std::vector<std::uint32_t> chart{std::uint32_t(seed)};
    chart_of[seed] = id;
    for (std::size_t head = 0; head < chart.size(); ++head) {
      const std::uint32_t t = chart[head];
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t n = surface.neighbour[3 * t + std::size_t(k)];
        if (n == kNoNeighbour || chart_of[n] != kNoNeighbour || glm::dot(normal[n], normal[seed]) < min_dot) continue;
        chart_of[n] = id;
        chart.push_back(n);
      }
    }
    charts.push_back(std::move(chart));
  }
  return charts;
}

std::vector<std::vector<std::uint32_t>> connected_pieces(const Surface& surface, const std::vector<std::uint32_t>& triangles) {
  // Membership by a sorted copy (a chart is a small part of the mesh).
  std::vector<std::uint32_t> sorted = triangles;
  std::sort(sorted.begin(), sorted.end());
  std::vector<std::uint8_t> taken(sorted.size(), 0);
  auto slot = [&](std::uint32_t t) -> std::ptrdiff_t {
    const auto it = std::lower_bound(sorted.begin(), sorted.end(), t);
    return it != sorted.end() && *it == t ? it - sorted.begin() : -1;
  };
  std::vector<std::vector<std::uint32_t>> pieces;
  for (std::uint32_t seed : triangles) {
    if (taken[std::size_t(slot(seed))]) continue;
    std::vector<std::uint32_t> piece{seed};
    taken[std::size_t(slot(seed))] = 1;
    for (std::size_t head = 0; head < piece.size(); ++head)
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t n = surface.neighbour[3 * std::size_t(piece[head]) + std::size_t(k)];
        const std::ptrdiff_t s = n == kNoNeighbour ? -1 : slot(n);
        if (s < 0 || taken[std::size_t(s)]) continue;
        taken[std::size_t(s)] = 1;
        piece.push_back(n);
      }
    pieces.push_back(std::move(piece));
  }
  return pieces;
}

}  // namespace prt::unwrap
