#include "mesh/vertex_footprint.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <unordered_map>

#include "core/error.h"
#include "core/hash.h"
#include "sh/sampling.h"

#include <glm/geometric.hpp>

namespace prt::mesh {

namespace {

// Equal bits of position and normal: copies of one smooth vertex (split for UVs or materials).
struct VertexKey {
  std::array<std::uint32_t, 6> bits;
  bool operator==(const VertexKey& o) const { return bits == o.bits; }
};
struct VertexKeyHash {
  std::size_t operator()(const VertexKey& k) const {
    std::uint64_t h = 0;
    for (std::uint32_t b : k.bits) h = mix64(h ^ b);
    return static_cast<std::size_t>(h);
  }
};

VertexKey key_of(const Mesh& mesh, std::size_t v) {
  VertexKey k{};
  const glm::vec3 n = v < mesh.normals.size() ? mesh.normals[v] : glm::vec3(0.0f);
  const float f[6] = {mesh.positions[v].x, mesh.positions[v].y, mesh.positions[v].z, n.x, n.y, n.z};
  for (int i = 0; i < 6; ++i) std::memcpy(&k.bits[static_cast<std::size_t>(i)], &f[i], sizeof(float));
  return k;
}

}  // namespace

VertexFootprints::VertexFootprints(const Mesh& mesh) : positions_(mesh.positions), indices_(&mesh.indices) {
  const std::vector<std::uint32_t>& idx = mesh.indices;
  group_.resize(positions_.size());
  std::unordered_map<VertexKey, std::uint32_t, VertexKeyHash> first_of;
  first_of.reserve(positions_.size());
  for (std::size_t v = 0; v < positions_.size(); ++v)
    group_[v] = first_of.emplace(key_of(mesh, v), static_cast<std::uint32_t>(v)).first->second;
  begin_.assign(positions_.size() + 1, 0);
  for (std::uint32_t v : idx) ++begin_[group_[v] + 1];
  for (std::size_t v = 0; v < positions_.size(); ++v) begin_[v + 1] += begin_[v];
  corners_.resize(idx.size());
  cumulative_area_.resize(idx.size());
  std::vector<std::uint32_t> next(begin_.begin(), begin_.end() - 1);
  for (std::size_t c = 0; c < idx.size(); ++c) corners_[next[group_[idx[c]]]++] = static_cast<std::uint32_t>(c);
  for (std::size_t v = 0; v < positions_.size(); ++v) {
    double sum = 0.0;
    for (std::uint32_t e = begin_[v]; e < begin_[v + 1]; ++e) {
      const std::size_t t = corners_[e] / 3 * 3;
      const glm::dvec3 a(positions_[idx[t]]), b(positions_[idx[t + 1]]), c(positions_[idx[t + 2]]);
      sum += 0.5 * glm::length(glm::cross(b - a, c - a));
      cumulative_area_[e] = sum;
    }
  }
}

double VertexFootprints::ring_area(std::uint32_t v) const {
  const std::uint32_t g = group_[v];
  return begin_[g + 1] > begin_[g] ? cumulative_area_[begin_[g + 1] - 1] : 0.0;
}

std::vector<std::uint32_t> VertexFootprints::footprint_corners(std::uint32_t v) const {
  const std::uint32_t g = group_[v];
  return std::vector<std::uint32_t>(corners_.begin() + begin_[g], corners_.begin() + begin_[g + 1]);
}

glm::vec3 VertexFootprints::point(std::uint32_t v, double u, double w, std::uint32_t* triangle) const {
  const std::uint32_t first = begin_[group_[v]], last = begin_[group_[v] + 1];
  const double total = ring_area(v);
  if (triangle) *triangle = kNoTriangle;
  if (!(total > 0.0)) return positions_[v];
  const double target = u * total;
  const auto it = std::upper_bound(cumulative_area_.begin() + first, cumulative_area_.begin() + last, target);
  const std::uint32_t e = std::min<std::uint32_t>(static_cast<std::uint32_t>(it - cumulative_area_.begin()), last - 1);
  const double below = e > first ? cumulative_area_[e - 1] : 0.0, share = cumulative_area_[e] - below;
  const double rescaled = share > 0.0 ? std::clamp((target - below) / share, 0.0, 1.0) : 0.5;
  const std::uint32_t corner = corners_[e], t = corner / 3 * 3, k = corner - t;
  if (triangle) *triangle = corner / 3;
  const std::vector<std::uint32_t>& idx = *indices_;
  const glm::dvec3 p(positions_[v]), a(positions_[idx[t + (k + 1) % 3]]), b(positions_[idx[t + (k + 2) % 3]]);
  const double own = beta22_quantile(rescaled), rest = 1.0 - own;
  return glm::vec3(own * p + rest * (w * a + (1.0 - w) * b));
}

glm::vec3 VertexFootprints::stratified_point(std::uint32_t v, std::uint32_t k, std::uint32_t scramble,
                                             std::uint32_t* triangle) const {
  const glm::dvec2 uw = sh::sobol_2d(k, scramble);
  return point(v, uw.x, uw.y, triangle);
}

std::unique_ptr<VertexFootprints> footprints_for(const Mesh& mesh, Footprint footprint) {
  return footprint == Footprint::area ? std::make_unique<VertexFootprints>(mesh) : nullptr;
}

const char* footprint_name(Footprint footprint) { return footprint == Footprint::area ? "area" : "vertex"; }

Footprint parse_footprint(const std::string& text, const std::string& option) {
  if (text == "area") return Footprint::area;
  if (text == "vertex") return Footprint::vertex;
  fail(option + ": expected area or vertex, got '" + text + "'");
}

int footprint_point_count(int samples) { return std::clamp(samples / kSamplesPerFootprintPoint, 1, kMaxFootprintPoints); }

double beta22_quantile(double u) {
  const double s = std::clamp(1.0 - 2.0 * u, -1.0, 1.0);
  return 0.5 - std::sin(std::asin(s) / 3.0);
}

}  // namespace prt::mesh
