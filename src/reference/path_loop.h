// Internal to prt_reference: the one path-tracing loop of both estimators, the Lambertian one
// (estimator.h) and the glossy one (glossy_estimator.h). Everything the two share lives here: waves of
// kPathsPerWave paths, next-event estimation with a shadow ray, one BSDF sample per vertex, the power
// heuristic, the tangent-plane rule, Russian roulette, and the fixed summation order. What varies is the
// surface model, a class `Surface` with
//   using Point = ...;  // a path vertex: at least `glm::dvec3 normal` (unit) and `glm::dvec3 origin`
//   void start_path(std::size_t j, const Point& start, Point& point);  // path j's copy of the start
//   bool light_terms(const Point& p, int depth, const glm::dvec3& w, glm::dvec3& rho, double& pdf);
//       // the cosine-weighted BRDF rho toward world direction w and the density of the BSDF strategy
//       // there; false where rho is zero
//   bool sample(const Point& p, int depth, glm::dvec2 u, BsdfSample& s);  // a BSDF-strategy sample
//   bool next_point(const trace::HitResult& hit, const glm::dvec3& direction, Point& next);
//       // the path vertex at a closest hit; false for a back face (the path ends)
// THE TANGENT-PLANE RULE. A direction below the tangent plane of the vertex (n . w <= 0) is not traced:
// it sees the environment. Only a BRDF that is non-zero there (the band-limited one of the glossy
// reference) notices; a Lambertian or true BRDF is zero there, so nothing is added.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "mesh/mesh.h"
#include "reference/environment_sampler.h"
#include "reference/estimator.h"
#include "sh/sampling.h"
#include "trace/scene.h"

namespace prt::reference::detail {

/// One sample of a BSDF strategy: world direction (unit), its density and weight = rho / pdf.
struct BsdfSample {
  glm::dvec3 direction{0.0, 0.0, 1.0};
  glm::dvec3 weight{0.0};
  double pdf = 0.0;
};

/// Power heuristic (Veach 1997, exponent 2) for a sample of density `own` against `other`.
inline double power_heuristic(double own, double other) {
  const double a = own * own, b = other * other;
  return a + b > 0.0 ? a / (a + b) : 0.0;
}

/// Where a closest hit lies on the mesh: its triangle, barycentric weights (w, u, v), position, unit
/// geometric normal ng, interpolated unit shading normal (ng where the interpolation vanishes) and the
/// origin of rays leaving it (position + ng * Scene::ray_offset(), on the front side).
struct HitGeometry {
  const std::uint32_t* triangle = nullptr;
  double w = 1.0, u = 0.0, v = 0.0;
  glm::dvec3 position{0.0}, geometric_normal{0.0, 1.0, 0.0}, normal{0.0, 1.0, 0.0}, origin{0.0};
};

/// The hit geometry of `hit` for a ray along `direction`, or false if it missed or met a back face:
/// the float face normal (p1 - p0) x (p2 - p0) of the counter-clockwise corners faces the ray.
bool hit_geometry(const mesh::Mesh& mesh, const trace::Scene& scene, const trace::HitResult& hit,
                  const glm::vec3& direction, HitGeometry& out);

/// Scratch memory of the loop for one thread (see PathWorkspace and GlossyWorkspace).
template <class Point>
struct PathBuffers {
  struct Path {
    Point point;
    glm::dvec3 throughput{1.0};
    glm::dvec3 value{0.0};    // this path's estimate so far
    std::uint32_t index = 0;  // path number within the estimate (the Sobol index)
    int depth = 0;            // surface depth of `point`
  };
  trace::RayBatch shadow{kPathsPerWave};
  trace::RayBatch bounce{kPathsPerWave};
  std::vector<Path> paths = std::vector<Path>(kPathsPerWave);
  std::vector<std::uint32_t> active, next_active;
  std::vector<glm::dvec3> shadow_contribution = std::vector<glm::dvec3>(kPathsPerWave);
  std::vector<std::uint32_t> shadow_owner = std::vector<std::uint32_t>(kPathsPerWave);
  std::vector<std::uint32_t> bounce_owner = std::vector<std::uint32_t>(kPathsPerWave);
  std::vector<glm::dvec3> bounce_direction = std::vector<glm::dvec3>(kPathsPerWave);
  std::vector<glm::dvec3> bounce_weight = std::vector<glm::dvec3>(kPathsPerWave);
  std::vector<double> bounce_pdf = std::vector<double>(kPathsPerWave);
};

/// The loop over one estimate's paths (see the top of this file and estimator.h, ESTIMATOR).
template <class Surface>
class PathLoop {
 public:
  using Point = typename Surface::Point;
  using Buffers = PathBuffers<Point>;

  PathLoop(Surface& surface, const trace::Scene& scene, const EnvironmentSampler& environment, int bounces,
           SampleStream& stream, Buffers& buffers)
      : surface_(surface), scene_(scene), environment_(environment), bounces_(bounces), stream_(stream), ws_(buffers) {}

  /// L_o at `start` from `paths` >= 1 paths, with its standard error and the rays traced.
  RadianceEstimate run(const Point& start, int paths) {
    glm::dvec3 sum(0.0), sum_sq(0.0);
    for (int first = 0; first < paths; first += kPathsPerWave) {
      const int wave = std::min(kPathsPerWave, paths - first);
      start_wave(start, first, wave);
      for (int depth = 0; !ws_.active.empty(); ++depth) {
        const bool last = depth >= bounces_;
        make_rays(depth);
        resolve_shadow_rays();
        resolve_bounce_rays(depth, last);
        std::swap(ws_.active, ws_.next_active);
      }
      for (int j = 0; j < wave; ++j) {  // in path order
        sum += ws_.paths[j].value;
        sum_sq += ws_.paths[j].value * ws_.paths[j].value;
      }
    }
    return mean_estimate(sum, sum_sq, paths, rays_);
  }

 private:
  using Path = typename Buffers::Path;

  void start_wave(const Point& start, int first, int wave) {
    ws_.active.clear();
    for (int j = 0; j < wave; ++j) {
      Path& path = ws_.paths[j];
      path.throughput = glm::dvec3(1.0);
      path.value = glm::dvec3(0.0);
      path.index = static_cast<std::uint32_t>(first + j);
      path.depth = 0;
      surface_.start_path(static_cast<std::size_t>(j), start, path.point);
      ws_.active.push_back(static_cast<std::uint32_t>(j));
    }
  }

  // One environment sample (a shadow ray above the tangent plane) and one BSDF sample per live path.
  void make_rays(int depth) {
    const bool light_sampling = environment_.has_distribution();
    ws_.shadow.clear();
    ws_.bounce.clear();
    for (std::uint32_t a : ws_.active) {
      Path& path = ws_.paths[a];
      const glm::vec3 origin(path.point.origin);
      if (light_sampling) add_light_sample(path, a, depth, origin);
      BsdfSample s;
      if (!surface_.sample(path.point, depth, sh::sobol_2d(path.index, stream_.dimension_seed(depth, 1)), s)) continue;
      const glm::dvec3 weight = path.throughput * s.weight;
      if (glm::dot(path.point.normal, s.direction) <= 0.0) {  // not traced: the environment
        const double light_pdf = light_sampling ? environment_.pdf(s.direction) : 0.0;
        path.value += weight * environment_.radiance(s.direction) * power_heuristic(s.pdf, light_pdf);
        continue;
      }
      const std::size_t k = ws_.bounce.push(origin, glm::vec3(s.direction));
      ws_.bounce_owner[k] = a;
      ws_.bounce_direction[k] = s.direction;
      ws_.bounce_weight[k] = weight;
      ws_.bounce_pdf[k] = s.pdf;
    }
  }

  void add_light_sample(Path& path, std::uint32_t a, int depth, const glm::vec3& origin) {
    const EnvironmentSampler::Sample s = environment_.sample(sh::sobol_2d(path.index, stream_.dimension_seed(depth, 0)));
    glm::dvec3 rho;
    double bsdf_pdf = 0.0;
    if (!surface_.light_terms(path.point, depth, s.direction, rho, bsdf_pdf) || rho == glm::dvec3(0.0)) return;
    const glm::dvec3 contribution =
        path.throughput * rho * environment_.radiance(s.direction) * (power_heuristic(s.pdf, bsdf_pdf) / s.pdf);
    if (glm::dot(path.point.normal, s.direction) <= 0.0) {
      path.value += contribution;  // below the tangent plane: not traced
    } else if (contribution != glm::dvec3(0.0)) {
      const std::size_t k = ws_.shadow.push(origin, glm::vec3(s.direction));
      ws_.shadow_contribution[k] = contribution;
      ws_.shadow_owner[k] = a;
    }
  }

  // Next-event estimation: unoccluded environment samples count.
  void resolve_shadow_rays() {
    if (ws_.shadow.empty()) return;
    scene_.occluded(ws_.shadow);
    rays_ += ws_.shadow.size();
    for (std::size_t k = 0; k < ws_.shadow.size(); ++k)
      if (!ws_.shadow.is_occluded(k)) ws_.paths[ws_.shadow_owner[k]].value += ws_.shadow_contribution[k];
  }

  // BSDF samples: escaping rays see the environment; front-face hits continue the path while bounces
  // remain (an occlusion query at the last bounce, where only escaping matters).
  void resolve_bounce_rays(int depth, bool last) {
    ws_.next_active.clear();
    if (ws_.bounce.empty()) return;
    rays_ += ws_.bounce.size();
    if (last) scene_.occluded(ws_.bounce);
    else scene_.intersect(ws_.bounce);
    const bool light_sampling = environment_.has_distribution();
    for (std::size_t k = 0; k < ws_.bounce.size(); ++k) {
      Path& path = ws_.paths[ws_.bounce_owner[k]];
      const glm::dvec3& direction = ws_.bounce_direction[k];
      const bool escaped = last ? !ws_.bounce.is_occluded(k) : !ws_.bounce.hit(k).hit();
      if (escaped) {
        const double light_pdf = light_sampling ? environment_.pdf(direction) : 0.0;
        path.value += ws_.bounce_weight[k] * environment_.radiance(direction) * power_heuristic(ws_.bounce_pdf[k], light_pdf);
        continue;
      }
      if (last || !surface_.next_point(ws_.bounce.hit(k), direction, path.point)) continue;  // a path that
      glm::dvec3 throughput = ws_.bounce_weight[k];  // ends here never reads its point again
      if (depth + 1 >= kRouletteDepth) {
        const double survive = std::min(1.0, std::max({std::abs(throughput.x), std::abs(throughput.y), std::abs(throughput.z)}));
        if (!(stream_.rng().next_double() < survive)) continue;
        throughput /= survive;
      }
      path.throughput = throughput;
      path.depth = depth + 1;
      ws_.next_active.push_back(ws_.bounce_owner[k]);
    }
  }

  Surface& surface_;
  const trace::Scene& scene_;
  const EnvironmentSampler& environment_;
  int bounces_;
  SampleStream& stream_;
  Buffers& ws_;
  std::uint64_t rays_ = 0;
};

}  // namespace prt::reference::detail
