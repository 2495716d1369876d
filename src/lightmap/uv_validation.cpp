#include "lightmap/uv_validation.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace prt::lightmap {

bool uv_zero_area(const glm::vec2& a, const glm::vec2& b, const glm::vec2& c) {
  const glm::dvec2 e1 = glm::dvec2(b) - glm::dvec2(a), e2 = glm::dvec2(c) - glm::dvec2(a), e3 = glm::dvec2(c) - glm::dvec2(b);
  const double twice_area = std::abs(e1.x * e2.y - e1.y * e2.x);
  const double longest_sq = std::max({glm::dot(e1, e1), glm::dot(e2, e2), glm::dot(e3, e3)});
  return !(twice_area > kZeroAreaRelative * longest_sq);
}

namespace {

enum class Range { inside, hair, outside };

Range uv_range(const glm::vec2* uv) {
  Range r = Range::inside;
  for (int k = 0; k < 3; ++k)
    for (int c = 0; c < 2; ++c) {
      const float x = uv[k][c];
      if (!(x >= -kUvHair && x <= 1.0f + kUvHair)) return Range::outside;  // also NaN
      if (x < 0.0f || x > 1.0f) r = Range::hair;
    }
  return r;
}

double area_of(const mesh::Mesh& mesh, std::size_t t) {
  const glm::dvec3 a(mesh.positions[mesh.indices[3 * t]]), b(mesh.positions[mesh.indices[3 * t + 1]]), c(mesh.positions[mesh.indices[3 * t + 2]]);
  return 0.5 * glm::length(glm::cross(b - a, c - a));
}

void note(std::size_t& count, std::vector<std::uint32_t>& examples, std::size_t t) {
  ++count;
  if (examples.size() < kMaxExamples) examples.push_back(std::uint32_t(t));
}

std::string percent(double share) {
  std::ostringstream s;
  s.precision(share < 0.001 ? 2 : 3);
  s << 100.0 * share << "%";
  return s.str();
}

// "triangle 4, 9" (or glTF sources), at most `most` of them, "and N more" for the rest.
std::string names(const mesh::Mesh& mesh, const std::vector<std::uint32_t>& triangles, std::size_t count, std::size_t most) {
  std::ostringstream s;
  const std::size_t shown = std::min(most, triangles.size());
  for (std::size_t k = 0; k < shown; ++k) s << (k ? ", " : "") << mesh::describe_triangle(mesh, triangles[k]);
  if (count > shown) s << " and " << count - shown << " more";
  return s.str();
}

// "triangles 0 and 4" (OBJ, PLY) or "node 1 mesh 0 primitive 0 triangle 3 and node ..." (glTF), each pair once.
std::string pairs(const mesh::Mesh& mesh, const std::vector<std::pair<std::uint32_t, std::uint32_t>>& examples) {
  std::ostringstream s;
  for (std::size_t k = 0; k < examples.size(); ++k) {
    if (std::find(examples.begin(), examples.begin() + std::ptrdiff_t(k), examples[k]) != examples.begin() + std::ptrdiff_t(k)) continue;
    if (s.tellp() > 0) s << ", ";
    if (mesh.triangle_source.empty())
      s << "triangles " << examples[k].first << " and " << examples[k].second;
    else
      s << mesh::describe_triangle(mesh, examples[k].first) << " and " << mesh::describe_triangle(mesh, examples[k].second);
  }
  return s.str();
}

}  // namespace

UvProblems check_uvs(const mesh::Mesh& mesh, const std::vector<std::uint8_t>* exclude) {
  UvProblems p;
  glm::vec2 lo(1e30f), hi(-1e30f);
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    if (exclude && (*exclude)[t]) continue;
    const glm::vec2* uv = mesh.lightmap_uv.data() + 3 * t;
    const double area = area_of(mesh, t);
    p.total_area += area;
    for (int k = 0; k < 3; ++k)
      if (std::isfinite(uv[k].x) && std::isfinite(uv[k].y)) lo = glm::min(lo, uv[k]), hi = glm::max(hi, uv[k]);
    const Range range = uv_range(uv);
    if (range == Range::outside) {
      note(p.outside, p.outside_examples, t);
      p.outside_area += area;
    } else if (uv_zero_area(uv[0], uv[1], uv[2])) {
      note(p.zero_area, p.zero_area_examples, t);
      p.zero_area_area += area;
    } else if (range == Range::hair) {
      note(p.clamped, p.clamped_examples, t);
    }
  }
  if (lo.x <= hi.x) p.uv_lo = lo, p.uv_hi = hi;
  return p;
}

void add_raster_checks(UvProblems& problems, const TexelSamples& samples) {
  problems.overlapping_texels = samples.overlapping_texels;
  problems.overlap_examples = samples.overlap_examples;
  problems.covered_texels = samples.samples.size();
}

double UvProblems::skipped_share() const { return total_area > 0.0 ? (outside_area + zero_area_area) / total_area : 0.0; }

bool UvProblems::tiling() const { return total_area > 0.0 && outside_area / total_area > kMaxDefectShare; }

bool UvProblems::refused() const {
  return skipped_share() > kMaxDefectShare || double(overlapping_texels) > kMaxDefectShare * double(std::max<std::size_t>(covered_texels, 1));
}

std::vector<std::uint8_t> UvProblems::skipped_triangles(const mesh::Mesh& mesh) const {
  std::vector<std::uint8_t> skip(mesh.triangle_count(), 0);
  if (outside + zero_area == 0) return skip;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const glm::vec2* uv = mesh.lightmap_uv.data() + 3 * t;
    skip[t] = uv_range(uv) == Range::outside || uv_zero_area(uv[0], uv[1], uv[2]);
  }
  return skip;
}

UvProblems check_texel_uvs(const mesh::Mesh& mesh, const std::vector<std::uint8_t>& per_vertex, std::vector<std::uint8_t>& skip) {
  UvProblems problems = check_uvs(mesh, per_vertex.empty() ? nullptr : &per_vertex);
  skip = problems.skipped_triangles(mesh);
  for (std::size_t t = 0; t < skip.size() && t < per_vertex.size(); ++t) skip[t] |= per_vertex[t];
  return problems;
}

std::string UvProblems::message(const mesh::Mesh& mesh) const {
  return problems(mesh) + "; generate lightmap UVs with --uv auto or prt unwrap";
}

std::string UvProblems::problems(const mesh::Mesh& mesh) const {
  std::ostringstream s;
  s << "lightmap UVs:";
  const char* sep = " ";
  if (outside > 0) {
    s << sep << outside << " triangle" << (outside == 1 ? " has" : "s have") << " UVs outside [0,1] (e.g. " << names(mesh, outside_examples, 0, 3) << ")";
    sep = "; ";
  }
  if (zero_area > 0) {
    s << sep << zero_area << " triangle" << (zero_area == 1 ? " is" : "s are") << " collapsed to zero UV area (e.g. "
      << names(mesh, zero_area_examples, 0, 3) << ")";
    sep = "; ";
  }
  if (overlapping_texels > 0) {
    s << sep << "overlapping charts: " << overlapping_texels << " texel centre" << (overlapping_texels == 1 ? " lies" : "s lie")
      << " inside two or more triangles (e.g. " << pairs(mesh, overlap_examples) << ")";
    sep = "; ";
  }
  const double overlap_share = double(overlapping_texels) / double(std::max<std::size_t>(covered_texels, 1));
  s << sep;
  if (skipped_share() > kMaxDefectShare || overlap_share <= kMaxDefectShare)
    s << "the skipped triangles would cover " << percent(skipped_share()) << " of the surface";
  else
    s << "the overlapping texels are " << percent(overlap_share) << " of the covered texels";
  s << ", more than the " << percent(kMaxDefectShare) << " prt repairs";
  if (tiling())
    s << "; UVs range over [" << uv_lo.x << ", " << uv_hi.x << "] x [" << uv_lo.y << ", " << uv_hi.y
      << "]: these look like tiling texture UVs (TEXCOORD_" << mesh.lightmap_uv_set << "), not lightmap UVs";
  return s.str();
}

std::vector<std::string> UvProblems::summary(const mesh::Mesh& mesh) const {
  std::vector<std::string> lines;
  if (clamped > 0)
    lines.push_back("lightmap UVs: " + std::to_string(clamped) + " triangle(s) with UVs at most 0.001 outside [0,1], clamped: " + names(mesh, clamped_examples, clamped, kMaxExamples));
  if (outside > 0)
    lines.push_back("lightmap UVs: " + std::to_string(outside) + " triangle(s) with UVs outside [0,1] (" + percent(outside_area / total_area) +
                    " of the surface) skipped, no texels of their own: " + names(mesh, outside_examples, outside, kMaxExamples));
  if (zero_area > 0)
    lines.push_back("lightmap UVs: " + std::to_string(zero_area) + " triangle(s) collapsed to zero UV area (" +
                    percent(zero_area_area / total_area) + " of the surface) skipped, no texels of their own: " +
                    names(mesh, zero_area_examples, zero_area, kMaxExamples));
  if (overlapping_texels > 0)
    lines.push_back("lightmap UVs: " + std::to_string(overlapping_texels) + " texel centre(s) inside two or more triangles (" +
                    percent(double(overlapping_texels) / double(std::max<std::size_t>(covered_texels, 1))) +
                    " of the texels) sampled on one of them: e.g. " + pairs(mesh, overlap_examples));
  return lines;
}

}  // namespace prt::lightmap
