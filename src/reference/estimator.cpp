#include "reference/estimator.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "core/constants.h"
#include "core/hash.h"
#include "mesh/texture.h"
#include "reference/path_loop.h"

namespace prt::reference {

namespace {


}  // namespace

struct PathWorkspace::Buffers : detail::PathBuffers<SurfacePoint> {
  trace::RayBatch single{1};
};

PathWorkspace::PathWorkspace() : buffers_(std::make_unique<Buffers>()) {
  buffers_->active.reserve(kPathsPerWave);
  buffers_->next_active.reserve(kPathsPerWave);
}
PathWorkspace::~PathWorkspace() = default;

SampleStream::SampleStream(std::uint64_t seed, std::uint64_t stream) : rng_(seed, stream) {
  base_seed_ = rng_.next_u32();
}

std::uint32_t SampleStream::dimension_seed(int depth, int pair) const {
  return mix32(base_seed_ ^ (0x9E3779B9u * static_cast<std::uint32_t>(2 * depth + pair + 1)));
}

PathTracer::PathTracer(const mesh::Mesh& mesh, const std::vector<glm::vec3>& albedo, const trace::Scene& scene,
                       const EnvironmentSampler& environment, const EstimatorOptions& options)
    : mesh_(mesh), albedo_(albedo), scene_(scene), environment_(environment), options_(options) {}

SurfacePoint PathTracer::vertex_point(std::uint32_t vertex) const {
  SurfacePoint point;
  point.normal = glm::normalize(glm::dvec3(mesh_.normals[vertex]));
  point.origin = glm::dvec3(scene_.offset_origin(mesh_.positions[vertex], mesh_.normals[vertex]));
  point.albedo = glm::dvec3(albedo_[vertex]);
  return point;
}

namespace detail {

bool hit_geometry(const mesh::Mesh& mesh, const trace::Scene& scene, const trace::HitResult& hit,
                  const glm::vec3& direction, HitGeometry& out) {
  if (!hit.hit()) return false;
  const std::uint32_t* tri = mesh.indices.data() + 3 * static_cast<std::size_t>(hit.prim_id);
  const glm::vec3& p0 = mesh.positions[tri[0]];
  const glm::vec3& p1 = mesh.positions[tri[1]];
  const glm::vec3& p2 = mesh.positions[tri[2]];
  // Front/back test exactly as the baker's gather: float face normal of the CCW corners.
  const glm::vec3 face_normal = glm::cross(p1 - p0, p2 - p0);
  if (glm::dot(face_normal, direction) >= 0.0f) return false;
  out.triangle = tri;
  out.u = hit.u;
  out.v = hit.v;
  out.w = 1.0 - out.u - out.v;
  out.position = out.w * glm::dvec3(p0) + out.u * glm::dvec3(p1) + out.v * glm::dvec3(p2);
  out.geometric_normal = glm::normalize(glm::dvec3(face_normal));
  const glm::dvec3 n = out.w * glm::dvec3(mesh.normals[tri[0]]) + out.u * glm::dvec3(mesh.normals[tri[1]]) +
                       out.v * glm::dvec3(mesh.normals[tri[2]]);
  const double length = glm::length(n);
  out.normal = length > 1e-12 ? n / length : out.geometric_normal;
  out.origin = out.position + out.geometric_normal * static_cast<double>(scene.ray_offset());
  return true;
}

}  // namespace detail

bool PathTracer::hit_point(const trace::HitResult& hit, const glm::vec3& direction, SurfacePoint& point) const {
  detail::HitGeometry g;
  if (!detail::hit_geometry(mesh_, scene_, hit, direction, g)) return false;
  point.normal = g.normal;
  point.origin = g.origin;
  point.surface = trace::TrueSurface{g.geometric_normal};
  const std::uint32_t* tri = g.triangle;
  if (mesh_.textured()) {  // the base colour at the hit (docs/conventions.md, "Albedo and textures")
    const auto triangle = static_cast<std::uint32_t>((tri - mesh_.indices.data()) / 3);
    point.albedo = glm::dvec3(mesh::base_color(mesh_, triangle, g.u, g.v));
    return true;
  }
  point.albedo = g.w * glm::dvec3(albedo_[tri[0]]) + g.u * glm::dvec3(albedo_[tri[1]]) + g.v * glm::dvec3(albedo_[tri[2]]);
  return true;
}

RadianceEstimate mean_estimate(const glm::dvec3& sum, const glm::dvec3& sum_sq, int paths, std::uint64_t rays) {
  RadianceEstimate estimate;
  const double n = static_cast<double>(paths);
  estimate.value = sum / n;
  if (paths > 1) {
    const glm::dvec3 variance = glm::max(sum_sq - sum * sum / n, glm::dvec3(0.0)) / (n - 1.0);
    estimate.standard_error = glm::sqrt(variance / n);
  }
  estimate.rays = rays;
  return estimate;
}

namespace {

// The Lambertian surface model of the path loop (path_loop.h): rho = albedo max(n.w, 0) / pi, BSDF
// samples cosine-distributed about n (sh::square_to_hemisphere_cosine), so rho / pdf = albedo; rho is 0
// below the point's triangle (the true-surface rule: such samples end the path).
class LambertSurface {
 public:
  using Point = SurfacePoint;
  explicit LambertSurface(const PathTracer& tracer) : tracer_(tracer) {}

  void start_path(std::size_t, const Point& start, Point& point) const { point = start; }

  bool light_terms(const Point& p, int, const glm::dvec3& w, glm::dvec3& rho, double& pdf) const {
    const double cosine = glm::dot(p.normal, w);
    if (!(cosine > 0.0) || !p.surface.admits(w)) return false;
    pdf = cosine * kInvPi;
    rho = p.albedo * pdf;
    return true;
  }

  bool sample(const Point& p, int, const glm::dvec2& u, detail::BsdfSample& s) const {
    glm::dvec3 t, b;
    sh::orthonormal_basis(p.normal, t, b);
    const glm::dvec3 local = sh::square_to_hemisphere_cosine(u);
    s.direction = glm::normalize(local.x * t + local.y * b + local.z * p.normal);
    if (!p.surface.admits(s.direction)) return false;  // below the true surface: no light
    s.pdf = local.z * kInvPi;
    s.weight = p.albedo;
    return true;
  }

  bool next_point(const trace::HitResult& hit, const glm::dvec3& direction, Point& next) const {
    return tracer_.hit_point(hit, glm::vec3(direction), next);
  }

 private:
  const PathTracer& tracer_;
};

}  // namespace

RadianceEstimate PathTracer::outgoing_radiance(const SurfacePoint& start, int paths, SampleStream& stream,
                                               PathWorkspace& workspace) const {
  LambertSurface surface(*this);
  detail::PathLoop<LambertSurface> loop(surface, scene_, environment_, options_.bounces, stream, workspace.buffers());
  return loop.run(start, paths);
}

RadianceEstimate PathTracer::incoming_radiance(const glm::dvec3& origin, const glm::dvec3& direction, int paths,
                                               SampleStream& stream, PathWorkspace& workspace) const {
  PathWorkspace::Buffers& ws = workspace.buffers();
  const glm::dvec3 dir = glm::normalize(direction);
  ws.single.clear();
  ws.single.push(glm::vec3(origin), glm::vec3(dir));
  scene_.intersect(ws.single);
  const trace::HitResult hit = ws.single.hit(0);
  RadianceEstimate estimate;
  if (!hit.hit()) {
    estimate.value = environment_.radiance(dir);
  } else {
    SurfacePoint point;
    if (hit_point(hit, glm::vec3(dir), point)) estimate = outgoing_radiance(point, paths, stream, workspace);
  }
  estimate.rays += 1;
  return estimate;
}

}  // namespace prt::reference
