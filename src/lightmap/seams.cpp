#include "lightmap/seams.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <unordered_map>

#include <Eigen/Sparse>
#include <glm/geometric.hpp>

#include "core/error.h"
#include "transfer/transfer_file.h"

namespace prt::lightmap {

namespace {

using PositionBits = std::array<std::uint32_t, 3>;

PositionBits bits(const glm::vec3& p) {
  PositionBits b;
  std::memcpy(b.data(), &p.x, 12);
  return b;
}

struct PositionEdge {
  PositionBits lo, hi;
  bool operator==(const PositionEdge& o) const { return lo == o.lo && hi == o.hi; }
};
struct PositionEdgeHash {
  std::size_t operator()(const PositionEdge& k) const {
    std::uint64_t h = 1469598103934665603ull;
    for (std::uint32_t v : k.lo) h = (h ^ v) * 1099511628211ull;
    for (std::uint32_t v : k.hi) h = (h ^ v) * 1099511628211ull;
    return std::size_t(h);
  }
};

// A triangle's edge k: corners k and k+1, ordered so that `lo` is the corner with the smaller position bits.
struct EdgeEnd {
  std::uint32_t triangle = 0;
  int corner[2] = {0, 0};  // corner indices (0..2) of the lo and hi ends
  int count = 0;           // how many triangles share the edge so far
};

// The bilinear footprint of `uv` in the texel grid: 4 texels and weights (clamped to the grid).
struct Footprint {
  std::uint32_t texel[4];
  double weight[4];
};

Footprint footprint(const glm::dvec2& uv, int width, int height) {
  const double x = uv.x * width - 0.5, y = uv.y * height - 0.5;
  const double fx = std::floor(x), fy = std::floor(y);
  const double tx = x - fx, ty = y - fy;
  auto clamp_i = [](double v, int n) { return std::uint32_t(std::clamp(long(v), 0L, long(n - 1))); };
  const std::uint32_t i0 = clamp_i(fx, width), i1 = clamp_i(fx + 1, width), j0 = clamp_i(fy, height), j1 = clamp_i(fy + 1, height);
  const auto w = std::uint32_t(width);
  return {{i0 + j0 * w, i1 + j0 * w, i0 + j1 * w, i1 + j1 * w},
          {(1 - tx) * (1 - ty), tx * (1 - ty), (1 - tx) * ty, tx * ty}};
}

}  // namespace

std::vector<SeamEdge> find_seams(const mesh::Mesh& mesh, float smooth_cos) {
  std::unordered_map<PositionEdge, EdgeEnd, PositionEdgeHash> edges;
  edges.reserve(mesh.indices.size());
  std::vector<SeamEdge> seams;
  std::vector<PositionEdge> seam_keys;
  for (std::uint32_t t = 0; t < mesh.triangle_count(); ++t)
    for (int k = 0; k < 3; ++k) {
      int c0 = k, c1 = (k + 1) % 3;
      PositionBits b0 = bits(mesh.positions[mesh.indices[3 * t + std::uint32_t(c0)]]),
                   b1 = bits(mesh.positions[mesh.indices[3 * t + std::uint32_t(c1)]]);
      if (b0 == b1) continue;
      if (b1 < b0) {
        std::swap(b0, b1);
        std::swap(c0, c1);
      }
      const PositionEdge key{b0, b1};
      EdgeEnd& e = edges[key];
      if (++e.count == 1) {
        e.triangle = t;
        e.corner[0] = c0;
        e.corner[1] = c1;
        continue;
      }
      if (e.count > 2) continue;  // non-manifold: dropped below
      const std::uint32_t a = e.triangle;
      SeamEdge s;
      s.triangle_a = a;
      s.triangle_b = t;
      bool differs = false, smooth = true;
      for (int end = 0; end < 2; ++end) {
        const std::uint32_t ca = 3 * a + std::uint32_t(e.corner[end]), cb = 3 * t + std::uint32_t(end == 0 ? c0 : c1);
        s.uv_a[end] = mesh.lightmap_uv[ca];
        s.uv_b[end] = mesh.lightmap_uv[cb];
        differs |= s.uv_a[end] != s.uv_b[end];
        smooth &= glm::dot(mesh.normals[mesh.indices[ca]], mesh.normals[mesh.indices[cb]]) >= smooth_cos;
      }
      if (differs && smooth) {
        seams.push_back(s);
        seam_keys.push_back(key);
      }
    }
  std::vector<SeamEdge> manifold;
  for (std::size_t i = 0; i < seams.size(); ++i)
    if (edges[seam_keys[i]].count == 2) manifold.push_back(seams[i]);
  return manifold;
}

StitchReport stitch_seams(std::vector<float>& values, std::vector<float>& bounce_only, std::size_t stride,
                          const std::vector<std::uint8_t>& coverage, int width, int height, const std::vector<SeamEdge>& seams,
                          const StitchOptions& o) {
  if (!(o.pull > 0.0) || !std::isfinite(o.pull)) fail_option("pull", " " + std::to_string(o.pull) + " must be finite and > 0");
  if (!(o.gutter_weight > 0.0) || !std::isfinite(o.gutter_weight))
    fail_option("gutter_weight", " " + std::to_string(o.gutter_weight) + " must be finite and > 0");
  if (o.samples_per_texel < 1 || o.samples_per_texel > 16)
    fail_option("samples_per_texel", " " + std::to_string(o.samples_per_texel) + " is out of range 1..16");
  StitchReport report;
  report.seams = seams.size();
  // Constraint rows: 8 (texel, weight) pairs each, side a positive, side b negative.
  std::vector<std::pair<std::uint32_t, double>> rows;
  const glm::dvec2 size(width, height);
  for (const SeamEdge& s : seams) {
    const double len = std::max(glm::length((glm::dvec2(s.uv_a[1]) - glm::dvec2(s.uv_a[0])) * size),
                                glm::length((glm::dvec2(s.uv_b[1]) - glm::dvec2(s.uv_b[0])) * size));
    const int n = std::max(4, int(std::ceil(len * o.samples_per_texel)));
    for (int k = 0; k < n; ++k) {
      const double t = (k + 0.5) / n;
      const Footprint fa = footprint(glm::mix(glm::dvec2(s.uv_a[0]), glm::dvec2(s.uv_a[1]), t), width, height);
      const Footprint fb = footprint(glm::mix(glm::dvec2(s.uv_b[0]), glm::dvec2(s.uv_b[1]), t), width, height);
      bool filled = true;
      for (int c = 0; c < 4; ++c)
        filled &= coverage[fa.texel[c]] != transfer::kTexelEmpty && coverage[fb.texel[c]] != transfer::kTexelEmpty;
      if (!filled) continue;
      for (int c = 0; c < 4; ++c) rows.emplace_back(fa.texel[c], fa.weight[c]);
      for (int c = 0; c < 4; ++c) rows.emplace_back(fb.texel[c], -fb.weight[c]);
      ++report.constraints;
    }
  }
  if (report.constraints == 0) return report;
  // Unknowns: the texels read, in texel order.
  std::vector<std::uint32_t> texels;
  for (const auto& r : rows) texels.push_back(r.first);
  std::sort(texels.begin(), texels.end());
  texels.erase(std::unique(texels.begin(), texels.end()), texels.end());
  report.texels = texels.size();
  auto unknown = [&](std::uint32_t texel) { return Eigen::Index(std::lower_bound(texels.begin(), texels.end(), texel) - texels.begin()); };
  std::vector<Eigen::Triplet<double>> triplets;
  for (std::size_t r = 0; r < report.constraints; ++r)
    for (int c = 0; c < 8; ++c) triplets.emplace_back(Eigen::Index(r), unknown(rows[8 * r + std::size_t(c)].first), rows[8 * r + std::size_t(c)].second);
  Eigen::SparseMatrix<double> A(Eigen::Index(report.constraints), Eigen::Index(texels.size()));
  A.setFromTriplets(triplets.begin(), triplets.end());
  Eigen::VectorXd d(Eigen::Index(texels.size()));
  for (std::size_t u = 0; u < texels.size(); ++u) d[Eigen::Index(u)] = coverage[texels[u]] == transfer::kTexelCovered ? 1.0 : o.gutter_weight;
  Eigen::SparseMatrix<double> M = o.pull * Eigen::SparseMatrix<double>(A.transpose() * A);
  for (Eigen::Index u = 0; u < d.size(); ++u) M.coeffRef(u, u) += d[u];
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(M);
  if (solver.info() != Eigen::Success) fail("seam stitching: the normal equations could not be factorised");
  auto solve = [&](std::vector<float>& grid) {
    Eigen::MatrixXd rhs(Eigen::Index(texels.size()), Eigen::Index(stride));
    for (std::size_t u = 0; u < texels.size(); ++u)
      for (std::size_t c = 0; c < stride; ++c) rhs(Eigen::Index(u), Eigen::Index(c)) = d[Eigen::Index(u)] * grid[texels[u] * stride + c];
    const Eigen::MatrixXd x = solver.solve(rhs);
    for (std::size_t u = 0; u < texels.size(); ++u)
      for (std::size_t c = 0; c < stride; ++c) grid[texels[u] * stride + c] = float(x(Eigen::Index(u), Eigen::Index(c)));
  };
  solve(values);
  if (!bounce_only.empty()) solve(bounce_only);
  return report;
}

}  // namespace prt::lightmap
