#include "reference/reference.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <string>

#include <glm/geometric.hpp>

#include "core/error.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "core/stopwatch.h"
#include "light/projection.h"
#include "reference/estimator.h"
#include "reference/vertex_driver.h"
#include "sh/basis.h"
#include "trace/scene.h"
#include "trace/true_surface.h"

namespace prt::reference {

namespace detail {

void summarise_noise(const std::vector<glm::vec3>& radiance, const std::vector<glm::dvec3>& error,
                     ReferenceReport& rep, std::vector<glm::vec3>* standard_error) {
  double largest = 0.0;
  for (const glm::vec3& r : radiance) largest = std::max(largest, sampling_magnitude(glm::dvec3(r)));
  double relative_sum = 0.0;
  std::size_t counted = 0;
  for (std::size_t v = 0; v < radiance.size(); ++v) {
    const double magnitude = sampling_magnitude(glm::dvec3(radiance[v]));
    if (magnitude <= 1e-6 * largest || magnitude == 0.0) continue;
    relative_sum += sampling_magnitude(error[v]) / magnitude;
    ++counted;
  }
  rep.mean_relative_standard_error = counted ? relative_sum / static_cast<double>(counted) : 0.0;
  if (standard_error) {
    standard_error->resize(radiance.size());
    for (std::size_t v = 0; v < radiance.size(); ++v) (*standard_error)[v] = glm::vec3(error[v]);
  }
}

}  // namespace detail

std::vector<glm::vec3> reference_albedo(const mesh::Mesh& mesh, const glm::vec3& fallback) {
  if (!mesh.albedo.empty()) return mesh.albedo;
  return std::vector<glm::vec3>(mesh.positions.size(), fallback);
}

void check_options(const ReferenceOptions& o) {
  if (o.samples < 1 || o.samples > kMaxSamples)
    fail_option("samples", " " + std::to_string(o.samples) + " is out of range 1.." + std::to_string(kMaxSamples));
  if (o.bounces < 0 || o.bounces > kMaxBounces)
    fail_option("bounces", " " + std::to_string(o.bounces) + " is out of range 0.." + std::to_string(kMaxBounces));
  for (int c = 0; c < 3; ++c)
    if (!(o.albedo[c] >= 0.0f && o.albedo[c] <= 1.0f)) fail_option("albedo", " components must lie in [0, 1]");
}

namespace {

// The diffuse estimate at every point: point k at positions[k], estimate(tracer, scene, k, stream, workspace).
template <class Estimate>
std::vector<glm::vec3> diffuse_radiance(const mesh::Mesh& mesh, const EnvironmentSampler& environment,
                                        const ReferenceOptions& options, const std::vector<glm::vec3>& positions,
                                        const char* label, ReferenceReport* report, std::vector<glm::vec3>* standard_error,
                                        const Estimate& estimate) {
  check_options(options);
  ReferenceReport local_report;
  ReferenceReport& rep = report ? *report : local_report;
  rep = ReferenceReport{};
  const std::vector<glm::vec3> albedo = reference_albedo(mesh, options.albedo);

  auto start = std::chrono::steady_clock::now();
  // One build thread: the BVH, and so closest-hit ties on shared edges, cannot depend on --threads.
  const trace::Scene scene(mesh, trace::SceneOptions{1, true});
  rep.seconds_build = seconds_since(start);
  const PathTracer tracer(mesh, albedo, scene, environment, EstimatorOptions{options.bounces});
  return detail::trace_every_vertex<PathWorkspace>(
      positions, label, options.seed, options.samples, options.threads, options.progress, options.dist, rep, standard_error,
      [&](std::uint32_t v, SampleStream& stream, PathWorkspace& workspace) {
        return estimate(tracer, scene, v, stream, workspace);
      });
}

}  // namespace

std::vector<glm::vec3> vertex_radiance(const mesh::Mesh& mesh, const EnvironmentSampler& environment,
                                       const ReferenceOptions& options, ReferenceReport* report,
                                       std::vector<glm::vec3>* standard_error) {
  const auto footprints = mesh::footprints_for(mesh, options.footprint);
  return diffuse_radiance(
      mesh, environment, options, mesh.positions, "reference", report, standard_error,
      [&](const PathTracer& tracer, const trace::Scene& scene, std::uint32_t v, SampleStream& stream, PathWorkspace& workspace) {
        if (!footprints) return tracer.outgoing_radiance(tracer.vertex_point(v), options.samples, stream, workspace);
        return detail::footprint_estimate(*footprints, v, options.seed, options.samples,
                                          [&](const glm::vec3& position, std::uint32_t triangle, int paths, SampleStream& run_stream) {
                                            SurfacePoint point = tracer.vertex_point(v);
                                            point.origin = glm::dvec3(scene.offset_origin(position, mesh.normals[v]));
                                            point.surface = trace::true_surface(mesh, triangle);
                                            return tracer.outgoing_radiance(point, paths, run_stream, workspace);
                                          });
      });
}

std::vector<glm::vec3> point_radiance(const mesh::Mesh& mesh, const EnvironmentSampler& environment,
                                      const ReferenceOptions& options, const std::vector<PointSample>& points,
                                      ReferenceReport* report) {
  std::vector<glm::vec3> positions;
  for (const PointSample& p : points) positions.push_back(p.position);
  return diffuse_radiance(mesh, environment, options, positions, "reference points", report, nullptr,
                          [&](const PathTracer& tracer, const trace::Scene& scene, std::uint32_t k, SampleStream& stream,
                              PathWorkspace& workspace) {
                            SurfacePoint point;
                            point.normal = glm::normalize(glm::dvec3(points[k].normal));
                            point.origin = glm::dvec3(scene.offset_origin(points[k].position, points[k].normal));
                            point.albedo = glm::dvec3(points[k].albedo);
                            point.surface = trace::true_surface(mesh, points[k].triangle);
                            return tracer.outgoing_radiance(point, options.samples, stream, workspace);
                          });
}

int band_limited_height(int bands) { return std::max(256, 16 * bands); }

light::Environment band_limited_environment(const light::Environment& environment, int bands, int threads) {
  if (bands < 1 || bands > sh::kMaxBands)
    fail_option("band_limit", ": expected a band count in 1.." + std::to_string(sh::kMaxBands) + ", got " + std::to_string(bands));
  const sh::RgbCoefficients coefficients = light::project(environment, bands, threads);
  const int height = band_limited_height(bands);
  light::Environment out;
  out.layout = light::Environment::Layout::equirect;
  out.equirect = light::render_equirect(coefficients, 2 * height, height, threads);
  out.source = environment.source + " (first " + std::to_string(bands) + " SH bands)";
  return out;
}

}  // namespace prt::reference
