#include "trace/hit_refine.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "trace/scene.h"

namespace prt::trace {
namespace {

void refine_one(RayHit& r, const std::vector<glm::vec3>& positions, const std::vector<std::uint32_t>& indices) {
  const std::size_t first = 3 * static_cast<std::size_t>(r.hit.prim_id);
  const glm::dvec3 p0 = glm::dvec3(positions[indices[first]]);
  const glm::dvec3 e1 = glm::dvec3(positions[indices[first + 1]]) - p0;
  const glm::dvec3 e2 = glm::dvec3(positions[indices[first + 2]]) - p0;
  const glm::dvec3 origin(r.ray.org_x, r.ray.org_y, r.ray.org_z), dir(r.ray.dir_x, r.ray.dir_y, r.ray.dir_z);
  const glm::dvec3 p = glm::cross(dir, e2);
  const double det = glm::dot(e1, p);
  if (!(std::fabs(det) > 0.0) || !std::isfinite(det)) return;
  const glm::dvec3 s = origin - p0, q = glm::cross(s, e1);
  double u = std::max(glm::dot(s, p) / det, 0.0), v = std::max(glm::dot(dir, q) / det, 0.0);
  if (u + v > 1.0) {
    const double sum = u + v;
    u /= sum;
    v /= sum;
  }
  const double t = std::max(glm::dot(e2, q) / det, static_cast<double>(r.ray.tnear));
  const glm::dvec3 ng = glm::cross(e1, e2);
  r.ray.tfar = static_cast<float>(t);
  r.hit.u = static_cast<float>(u);
  r.hit.v = static_cast<float>(v);
  r.hit.ng_x = static_cast<float>(ng.x);
  r.hit.ng_y = static_cast<float>(ng.y);
  r.hit.ng_z = static_cast<float>(ng.z);
}

}  // namespace

void refine_hits(RayHit* records, std::size_t count, const std::vector<glm::vec3>& positions,
                 const std::vector<std::uint32_t>& indices) {
  for (std::size_t i = 0; i < count; ++i)
    if (records[i].hit.geom_id != kNoHit) refine_one(records[i], positions, indices);
}

}  // namespace prt::trace
