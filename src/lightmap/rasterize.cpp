#include "lightmap/rasterize.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "core/parallel.h"
#include "lightmap/uv_validation.h"
#include "mesh/texture.h"
#include "transfer/transfer_file.h"

namespace prt::lightmap {

namespace {

constexpr int kRowsPerBand = 8;
constexpr std::uint32_t kNone = 0xffffffffu;

// Twice the signed area of (a, b, p).
double edge(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& p) {
  return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
}

// A UV triangle in texel units with what the per-texel tests need.
struct UvTriangle {
  glm::dvec2 p[3];
  double twice_area = 0.0;  // signed
  glm::dvec2 lo, hi;

  glm::dvec3 barycentric(const glm::dvec2& q) const {
    return glm::dvec3(edge(p[1], p[2], q), edge(p[2], p[0], q), edge(p[0], p[1], q)) / twice_area;
  }

  // Positive-area overlap with the square [i, i+1] x [j, j+1] (separating axis test, strict).
  bool overlaps_square(int i, int j) const {
    if (!(lo.x < i + 1 && hi.x > i && lo.y < j + 1 && hi.y > j)) return false;
    const glm::dvec2 corners[4] = {{i, j}, {i + 1, j}, {i, j + 1}, {i + 1, j + 1}};
    for (int e = 0; e < 3; ++e) {
      const glm::dvec2& a = p[e];
      const glm::dvec2& b = p[(e + 1) % 3];
      const double inside_sign = twice_area > 0 ? 1.0 : -1.0;
      // The square lies entirely on the outer side of (or on) the edge line: separated.
      bool all_outside = true;
      for (const glm::dvec2& c : corners) all_outside = all_outside && inside_sign * edge(a, b, c) <= 0.0;
      if (all_outside) return false;
    }
    return true;
  }

  // The point of the triangle's part inside texel (i, j) nearest to the texel centre q (outside the
  // triangle), and its squared distance: a point on the boundary of the triangle clipped to the
  // texel's square (a convex polygon), so the sample stays in its texel.
  glm::dvec2 nearest_in_texel(const glm::dvec2& q, int i, int j, double* distance_sq) const {
    Polygon poly;
    poly.size = 3;
    for (int k = 0; k < 3; ++k) poly.p[k] = p[k];
    poly = clip(clip(clip(clip(poly, 0, double(i), -1.0), 0, double(i + 1), 1.0), 1, double(j), -1.0), 1, double(j + 1), 1.0);
    if (poly.size == 0) {  // only by rounding: fall back to the whole triangle
      poly.size = 3;
      for (int k = 0; k < 3; ++k) poly.p[k] = p[k];
    }
    glm::dvec2 best = poly.p[0];
    double best_sq = std::numeric_limits<double>::infinity();
    for (int e = 0; e < poly.size; ++e) {
      const glm::dvec2 a = poly.p[e], d = poly.p[(e + 1) % poly.size] - poly.p[e];
      const double length_sq = glm::dot(d, d);
      const double t = length_sq > 0.0 ? std::clamp(glm::dot(q - a, d) / length_sq, 0.0, 1.0) : 0.0;
      const glm::dvec2 c = a + t * d;
      const double sq = glm::dot(q - c, q - c);
      if (sq < best_sq) best_sq = sq, best = c;
    }
    *distance_sq = best_sq;
    return best;
  }

  // A convex polygon of at most 3 + 4 corners (a triangle clipped by four lines).
  struct Polygon {
    glm::dvec2 p[8];
    int size = 0;
  };

  // The part of `poly` on the side sign * (x[axis] - limit) <= 0 (Sutherland-Hodgman, one line).
  static Polygon clip(const Polygon& poly, int axis, double limit, double sign) {
    Polygon out;
    for (int k = 0; k < poly.size; ++k) {
      const glm::dvec2 a = poly.p[k], b = poly.p[(k + 1) % poly.size];
      const double da = sign * (a[axis] - limit), db = sign * (b[axis] - limit);
      if (da <= 0.0 && out.size < 8) out.p[out.size++] = a;
      if (((da < 0.0 && db > 0.0) || (da > 0.0 && db < 0.0)) && out.size < 8) out.p[out.size++] = a + (b - a) * (da / (da - db));
    }
    return out;
  }
};

UvTriangle uv_triangle(const mesh::Mesh& mesh, std::size_t t, int width, int height) {
  UvTriangle tri;
  for (int k = 0; k < 3; ++k) {
    const glm::vec2 uv = mesh.lightmap_uv[3 * t + k];
    tri.p[k] = glm::dvec2(std::clamp(double(uv.x), 0.0, 1.0) * width, std::clamp(double(uv.y), 0.0, 1.0) * height);
  }
  tri.twice_area = edge(tri.p[0], tri.p[1], tri.p[2]);
  tri.lo = glm::min(tri.p[0], glm::min(tri.p[1], tri.p[2]));
  tri.hi = glm::max(tri.p[0], glm::max(tri.p[1], tri.p[2]));
  return tri;
}

// Per texel while rasterizing: the owner so far, the first triangle strictly containing the centre, and
// whether a second one was counted (Overlaps: one count per texel however many triangles stack there).
struct TexelState {
  double distance_sq = std::numeric_limits<double>::infinity();
  std::uint32_t owner = kNone, inside = kNone;
  bool overlapped = false;
  glm::dvec2 nearest{0.0};
};

struct Overlaps {
  std::size_t texels = 0;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> examples;
};

// Rasterizes triangle t into the rows [row_begin, row_end) of `state`.
void rasterize_triangle(const UvTriangle& tri, std::uint32_t t, int width, int row_begin, int row_end,
                        std::vector<TexelState>& state, Overlaps& overlaps) {
  const int i0 = std::max(0, int(std::floor(tri.lo.x))), i1 = std::min(width - 1, int(std::ceil(tri.hi.x)) - 1);
  const int j0 = std::max(row_begin, int(std::floor(tri.lo.y))), j1 = std::min(row_end - 1, int(std::ceil(tri.hi.y)) - 1);
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) {
      if (!tri.overlaps_square(i, j)) continue;
      const glm::dvec2 centre(i + 0.5, j + 0.5);
      TexelState& s = state[std::size_t(i) + std::size_t(j) * std::size_t(width)];
      const glm::dvec3 w = tri.barycentric(centre);
      if (w.x > kInsideEpsilon && w.y > kInsideEpsilon && w.z > kInsideEpsilon) {
        if (s.inside == kNone) {
          s.inside = t;
        } else if (!s.overlapped) {
          s.overlapped = true;
          ++overlaps.texels;
          if (overlaps.examples.size() < 3) overlaps.examples.emplace_back(s.inside, t);
        }
      }
      if (w.x >= 0.0 && w.y >= 0.0 && w.z >= 0.0) {
        if (s.distance_sq > 0.0) s.distance_sq = 0.0, s.owner = t, s.nearest = centre;  // equal: the lower index stays
        continue;
      }
      if (s.distance_sq == 0.0) continue;  // a triangle containing the centre owns it
      double sq = 0.0;
      const glm::dvec2 q = tri.nearest_in_texel(centre, i, j, &sq);
      if (sq < s.distance_sq) s.distance_sq = sq, s.owner = t, s.nearest = q;
    }
}

TexelSample make_sample(const mesh::Mesh& mesh, const std::vector<glm::vec3>& albedo, const UvTriangle& tri,
                        std::uint32_t texel, std::uint32_t t, const glm::dvec2& q) {
  glm::dvec3 w = glm::clamp(tri.barycentric(q), 0.0, 1.0);
  w /= (w.x + w.y + w.z);
  TexelSample s;
  s.texel = texel;
  s.triangle = t;
  s.barycentric = glm::vec3(w);
  const std::uint32_t* idx = mesh.indices.data() + 3 * std::size_t(t);
  glm::dvec3 position(0.0), normal(0.0), colour(0.0);
  for (int k = 0; k < 3; ++k) {
    position += w[k] * glm::dvec3(mesh.positions[idx[k]]);
    normal += w[k] * glm::dvec3(mesh.normals[idx[k]]);
    colour += w[k] * glm::dvec3(albedo[idx[k]]);
  }
  s.position = glm::vec3(position);
  const double length = glm::length(normal);
  if (length > 0.0) s.normal = glm::vec3(normal / length);
  // Textured: the base colour at the texel's point (docs/conventions.md, "Albedo and textures").
  s.albedo = mesh.textured() ? mesh::base_color(mesh, t, w.y, w.z) : glm::vec3(colour);
  return s;
}

}  // namespace

TexelSamples rasterize(const mesh::Mesh& mesh, const std::vector<glm::vec3>& albedo, int width, int height, int threads,
                       const std::vector<std::uint8_t>* skip) {
  TexelSamples out;
  out.width = width;
  out.height = height;
  const std::size_t triangles = mesh.triangle_count();
  std::vector<UvTriangle> tris(triangles);
  const int bands = (height + kRowsPerBand - 1) / kRowsPerBand;
  std::vector<std::vector<std::uint32_t>> band_triangles(static_cast<std::size_t>(bands));
  for (std::size_t t = 0; t < triangles; ++t) {
    if (skip && (*skip)[t]) continue;
    if (uv_zero_area(mesh.lightmap_uv[3 * t], mesh.lightmap_uv[3 * t + 1], mesh.lightmap_uv[3 * t + 2])) continue;
    tris[t] = uv_triangle(mesh, t, width, height);
    if (tris[t].twice_area == 0.0) continue;
    const int b0 = std::max(0, int(std::floor(tris[t].lo.y)) / kRowsPerBand);
    const int b1 = std::min(bands - 1, std::max(0, int(std::ceil(tris[t].hi.y)) - 1) / kRowsPerBand);
    for (int b = b0; b <= b1; ++b) band_triangles[std::size_t(b)].push_back(std::uint32_t(t));
  }
  std::vector<TexelState> state(std::size_t(width) * std::size_t(height));
  std::vector<Overlaps> overlaps(static_cast<std::size_t>(bands));
  parallel_for(static_cast<std::size_t>(bands), 1, threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t b = begin; b < end; ++b) {
      const int row_begin = int(b) * kRowsPerBand, row_end = std::min(height, row_begin + kRowsPerBand);
      for (std::uint32_t t : band_triangles[b]) rasterize_triangle(tris[t], t, width, row_begin, row_end, state, overlaps[b]);
    }
  });
  out.coverage.assign(state.size(), transfer::kTexelEmpty);
  out.samples.reserve(std::size_t(std::count_if(state.begin(), state.end(), [](const TexelState& s) { return s.owner != kNone; })));
  for (std::size_t texel = 0; texel < state.size(); ++texel) {
    const TexelState& s = state[texel];
    if (s.owner == kNone) continue;
    out.coverage[texel] = transfer::kTexelCovered;
    out.samples.push_back(make_sample(mesh, albedo, tris[s.owner], std::uint32_t(texel), s.owner, s.nearest));
  }
  for (const Overlaps& o : overlaps) {
    out.overlapping_texels += o.texels;
    for (const auto& e : o.examples)
      if (out.overlap_examples.size() < 3) out.overlap_examples.push_back(e);
  }
  return out;
}

}  // namespace prt::lightmap
