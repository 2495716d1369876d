#include "reference/estimator.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace prt::reference {

namespace {

constexpr double kInvPi = 0.31830988618379067154;

// Orthonormal frame (t, b, n) about a unit normal (Duff et al. 2017, "Building an Orthonormal Basis,
// Revisited", JCGT 6(1)).
struct Frame {
  glm::dvec3 t, b, n;
  explicit Frame(const glm::dvec3& normal) : n(normal) {
    const double sign = std::copysign(1.0, n.z);
    const double a = -1.0 / (sign + n.z);
    const double c = n.x * n.y * a;
    t = glm::dvec3(1.0 + sign * n.x * n.x * a, sign * c, -sign * n.x);
    b = glm::dvec3(c, sign + n.y * n.y * a, -n.y);
  }
  glm::dvec3 to_world(const glm::dvec3& local) const { return local.x * t + local.y * b + local.z * n; }
};

// Power heuristic (Veach 1997, exponent 2) for a sample of density `own` against `other`.
double power_heuristic(double own, double other) {
  const double a = own * own, b = other * other;
  return a + b > 0.0 ? a / (a + b) : 0.0;
}

glm::vec3 to_float(const glm::dvec3& v) { return glm::vec3(v); }

}  // namespace

struct PathWorkspace::Buffers {
  struct Path {
    SurfacePoint point;
    glm::dvec3 throughput{1.0};
    glm::dvec3 value{0.0};  // this path's estimate so far
    std::uint32_t index = 0;  // path number within the estimate (Sobol index)
  };
  trace::RayBatch shadow{kPathsPerWave};
  trace::RayBatch bounce{kPathsPerWave};
  trace::RayBatch single{1};
  std::vector<Path> paths = std::vector<Path>(kPathsPerWave);
  std::vector<std::uint32_t> active, next_active;
  std::vector<glm::dvec3> shadow_contribution = std::vector<glm::dvec3>(kPathsPerWave);
  std::vector<std::uint32_t> shadow_owner = std::vector<std::uint32_t>(kPathsPerWave);
  std::vector<std::uint32_t> bounce_owner = std::vector<std::uint32_t>(kPathsPerWave);
  std::vector<glm::dvec3> bounce_direction = std::vector<glm::dvec3>(kPathsPerWave);
  std::vector<double> bounce_pdf = std::vector<double>(kPathsPerWave);
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
  // A 32-bit integer hash (Wellons' "lowbias32") of the base seed combined with the dimension pair.
  std::uint32_t x = base_seed_ ^ (0x9E3779B9u * static_cast<std::uint32_t>(2 * depth + pair + 1));
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

PathTracer::PathTracer(const mesh::Mesh& mesh, const std::vector<glm::vec3>& albedo, const trace::Scene& scene,
                       const EnvironmentSampler& environment, const EstimatorOptions& options)
    : mesh_(mesh), albedo_(albedo), scene_(scene), environment_(environment), options_(options) {}

SurfacePoint PathTracer::vertex_point(std::uint32_t vertex) const {
  SurfacePoint point;
  point.normal = glm::normalize(glm::dvec3(mesh_.normals[vertex]));
  point.ray_origin = glm::dvec3(scene_.offset_origin(mesh_.positions[vertex], mesh_.normals[vertex]));
  point.albedo = glm::dvec3(albedo_[vertex]);
  return point;
}

bool PathTracer::hit_point(const trace::HitResult& hit, const glm::vec3& direction, SurfacePoint& point) const {
  if (!hit.hit()) return false;
  const std::uint32_t* tri = mesh_.indices.data() + 3 * static_cast<std::size_t>(hit.prim_id);
  const glm::vec3& p0 = mesh_.positions[tri[0]];
  const glm::vec3& p1 = mesh_.positions[tri[1]];
  const glm::vec3& p2 = mesh_.positions[tri[2]];
  // Front/back test exactly as the baker's gather: float face normal of the CCW corners.
  const glm::vec3 face_normal = glm::cross(p1 - p0, p2 - p0);
  if (glm::dot(face_normal, direction) >= 0.0f) return false;
  const double u = hit.u, v = hit.v, w = 1.0 - u - v;
  const glm::dvec3 position = w * glm::dvec3(p0) + u * glm::dvec3(p1) + v * glm::dvec3(p2);
  const glm::dvec3 ng = glm::normalize(glm::dvec3(face_normal));
  const glm::dvec3 n = w * glm::dvec3(mesh_.normals[tri[0]]) + u * glm::dvec3(mesh_.normals[tri[1]]) +
                       v * glm::dvec3(mesh_.normals[tri[2]]);
  const double length = glm::length(n);
  point.normal = length > 1e-12 ? n / length : ng;
  point.ray_origin = position + ng * static_cast<double>(scene_.ray_offset());
  point.albedo = w * glm::dvec3(albedo_[tri[0]]) + u * glm::dvec3(albedo_[tri[1]]) + v * glm::dvec3(albedo_[tri[2]]);
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

RadianceEstimate PathTracer::outgoing_radiance(const SurfacePoint& start, int paths, SampleStream& stream,
                                               PathWorkspace& workspace) const {
  PathWorkspace::Buffers& ws = workspace.buffers();
  sh::Rng& rng = stream.rng();
  const bool light_sampling = environment_.has_distribution();
  glm::dvec3 sum(0.0), sum_sq(0.0);
  std::uint64_t rays = 0;

  for (int first = 0; first < paths; first += kPathsPerWave) {
    const int wave = std::min(kPathsPerWave, paths - first);
    ws.active.clear();
    for (int j = 0; j < wave; ++j) {
      ws.paths[j] = PathWorkspace::Buffers::Path{start, glm::dvec3(1.0), glm::dvec3(0.0),
                                                 static_cast<std::uint32_t>(first + j)};
      ws.active.push_back(static_cast<std::uint32_t>(j));
    }
    for (int depth = 0; !ws.active.empty(); ++depth) {
      const bool last = depth >= options_.bounces;
      ws.shadow.clear();
      ws.bounce.clear();
      // Generate one environment sample and one BSDF sample per live path.
      for (std::uint32_t a : ws.active) {
        PathWorkspace::Buffers::Path& path = ws.paths[a];
        const Frame frame(path.point.normal);
        const glm::vec3 origin = to_float(path.point.ray_origin);
        const glm::dvec3 weight = path.throughput * path.point.albedo;
        if (light_sampling) {
          const glm::dvec2 u = sh::sobol_2d(path.index, stream.dimension_seed(depth, 0));
          const EnvironmentSampler::Sample s = environment_.sample(u);
          const double cosine = glm::dot(path.point.normal, s.direction);
          if (cosine > 0.0) {
            const double bsdf_pdf = cosine * kInvPi;
            const glm::dvec3 contribution = weight * environment_.radiance(s.direction) *
                                            (bsdf_pdf / s.pdf * power_heuristic(s.pdf, bsdf_pdf));
            if (contribution != glm::dvec3(0.0)) {
              const std::size_t k = ws.shadow.push(origin, to_float(s.direction));
              ws.shadow_contribution[k] = contribution;
              ws.shadow_owner[k] = a;
            }
          }
        }
        const glm::dvec2 u = sh::sobol_2d(path.index, stream.dimension_seed(depth, 1));
        const glm::dvec3 local = sh::square_to_hemisphere_cosine(u);
        const glm::dvec3 direction = glm::normalize(frame.to_world(local));
        const std::size_t k = ws.bounce.push(origin, to_float(direction));
        ws.bounce_owner[k] = a;
        ws.bounce_direction[k] = direction;
        ws.bounce_pdf[k] = local.z * kInvPi;
      }

      // Next-event estimation: unoccluded environment samples count.
      if (!ws.shadow.empty()) {
        scene_.occluded(ws.shadow);
        rays += ws.shadow.size();
        for (std::size_t k = 0; k < ws.shadow.size(); ++k)
          if (!ws.shadow.is_occluded(k)) ws.paths[ws.shadow_owner[k]].value += ws.shadow_contribution[k];
      }

      // BSDF samples: escaping rays see the environment; front-face hits continue the path.
      rays += ws.bounce.size();
      ws.next_active.clear();
      if (last) scene_.occluded(ws.bounce);
      else scene_.intersect(ws.bounce);
      for (std::size_t k = 0; k < ws.bounce.size(); ++k) {
        PathWorkspace::Buffers::Path& path = ws.paths[ws.bounce_owner[k]];
        const glm::dvec3& direction = ws.bounce_direction[k];
        const bool escaped = last ? !ws.bounce.is_occluded(k) : !ws.bounce.hit(k).hit();
        const glm::dvec3 weight = path.throughput * path.point.albedo;
        if (escaped) {
          const double light_pdf = light_sampling ? environment_.pdf(direction) : 0.0;
          path.value += weight * environment_.radiance(direction) * power_heuristic(ws.bounce_pdf[k], light_pdf);
          continue;
        }
        if (last) continue;
        SurfacePoint next;
        const trace::Ray& ray = ws.bounce.data()[k].ray;
        if (!hit_point(ws.bounce.hit(k), glm::vec3(ray.dir_x, ray.dir_y, ray.dir_z), next)) continue;
        glm::dvec3 throughput = weight;
        if (depth + 1 >= kRouletteDepth) {
          const double survive = std::min(1.0, std::max({throughput.x, throughput.y, throughput.z}));
          if (!(rng.next_double() < survive)) continue;
          throughput /= survive;
        }
        path.point = next;
        path.throughput = throughput;
        ws.next_active.push_back(ws.bounce_owner[k]);
      }
      std::swap(ws.active, ws.next_active);
    }

    // Sum the wave's paths in path order.
    for (int j = 0; j < wave; ++j) {
      sum += ws.paths[j].value;
      sum_sq += ws.paths[j].value * ws.paths[j].value;
    }
  }

  return mean_estimate(sum, sum_sq, paths, rays);
}

RadianceEstimate PathTracer::incoming_radiance(const glm::dvec3& origin, const glm::dvec3& direction, int paths,
                                               SampleStream& stream, PathWorkspace& workspace) const {
  PathWorkspace::Buffers& ws = workspace.buffers();
  const glm::dvec3 dir = glm::normalize(direction);
  ws.single.clear();
  ws.single.push(to_float(origin), to_float(dir));
  scene_.intersect(ws.single);
  const trace::HitResult hit = ws.single.hit(0);
  RadianceEstimate estimate;
  if (!hit.hit()) {
    estimate.value = environment_.radiance(dir);
  } else {
    SurfacePoint point;
    if (hit_point(hit, to_float(dir), point)) estimate = outgoing_radiance(point, paths, stream, workspace);
  }
  estimate.rays += 1;
  return estimate;
}

}  // namespace prt::reference
