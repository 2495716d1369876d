#include "lightmap/uv_validation.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <glm/geometric.hpp>

namespace prt::lightmap {

bool uv_zero_area(const glm::vec2& a, const glm::vec2& b, const glm::vec2& c) {
  const glm::dvec2 e1 = glm::dvec2(b) - glm::dvec2(a), e2 = glm::dvec2(c) - glm::dvec2(a), e3 = glm::dvec2(c) - glm::dvec2(b);
  const double twice_area = std::abs(e1.x * e2.y - e1.y * e2.x);
  const double longest_sq = std::max({glm::dot(e1, e1), glm::dot(e2, e2), glm::dot(e3, e3)});
  return !(twice_area > kZeroAreaRelative * longest_sq);
}

UvProblems check_uvs(const mesh::Mesh& mesh) {
  UvProblems p;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const glm::vec2* uv = mesh.lightmap_uv.data() + 3 * t;
    bool outside = false;
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 2; ++c) outside = outside || !(uv[k][c] >= 0.0f && uv[k][c] <= 1.0f);
    if (outside) {
      ++p.outside;
      if (p.outside_examples.size() < 3) p.outside_examples.push_back(std::uint32_t(t));
      continue;  // a non-finite UV has no area to speak of
    }
    if (uv_zero_area(uv[0], uv[1], uv[2])) {
      ++p.zero_area;
      if (p.zero_area_examples.size() < 3) p.zero_area_examples.push_back(std::uint32_t(t));
    }
  }
  return p;
}

namespace {

std::string examples(const std::vector<std::uint32_t>& triangles) {
  std::ostringstream s;
  s << (triangles.size() == 1 ? "triangle " : "triangles ");
  for (std::size_t k = 0; k < triangles.size(); ++k) s << (k ? ", " : "") << triangles[k];
  return s.str();
}

}  // namespace

std::string UvProblems::message() const {
  std::ostringstream s;
  s << "lightmap UVs:";
  const char* sep = " ";
  if (outside > 0) {
    s << sep << outside << " triangle" << (outside == 1 ? " has" : "s have") << " UVs outside [0,1] (e.g. "
      << examples(outside_examples) << ")";
    sep = "; ";
  }
  if (zero_area > 0) {
    s << sep << zero_area << " triangle" << (zero_area == 1 ? " is" : "s are") << " collapsed to zero UV area (e.g. "
      << examples(zero_area_examples) << ")";
    sep = "; ";
  }
  if (overlapping_texels > 0) {
    s << sep << "overlapping charts: " << overlapping_texels << " texel centre" << (overlapping_texels == 1 ? " lies" : "s lie")
      << " inside two triangles (e.g. ";
    for (std::size_t k = 0; k < overlap_examples.size(); ++k)
      s << (k ? ", " : "") << "triangles " << overlap_examples[k].first << " and " << overlap_examples[k].second;
    s << ")";
  }
  return s.str();
}

}  // namespace prt::lightmap
