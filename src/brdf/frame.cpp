#include "brdf/frame.h"

#include <cmath>

namespace prt::brdf {

namespace {

template <typename T>
glm::mat<3, 3, T> frame_of(const glm::vec<3, T>& n) {
  // Y x n = (n.z, 0, -n.x).
  const T length = std::sqrt(n.z * n.z + n.x * n.x);
  glm::vec<3, T> t;
  if (length >= T(1e-6)) {
    t = glm::vec<3, T>(n.z / length, 0, -n.x / length);
  } else {  // at a pole: X made orthogonal to n
    t = glm::vec<3, T>(1 - n.x * n.x, -n.x * n.y, -n.x * n.z);
    t /= std::sqrt(t.x * t.x + t.y * t.y + t.z * t.z);
  }
  // b = n x t
  const glm::vec<3, T> b(n.y * t.z - n.z * t.y, n.z * t.x - n.x * t.z, n.x * t.y - n.y * t.x);
  return glm::mat<3, 3, T>(t, b, n);
}

}  // namespace

glm::dmat3 shading_frame(const glm::dvec3& normal) { return frame_of(normal); }
glm::mat3 shading_frame(const glm::vec3& normal) { return frame_of(normal); }

}  // namespace prt::brdf
