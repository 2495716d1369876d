// The per-vertex driver of the glossy reference (glossy_estimator.h).
#include <chrono>

#include <glm/geometric.hpp>

#include "reference/glossy_estimator.h"
#include "reference/vertex_driver.h"

namespace prt::reference {

GlossyReferenceOptions glossy_run_options(const ReferenceOptions& shared) {
  GlossyReferenceOptions glossy;
  glossy.samples = shared.samples;
  glossy.seed = shared.seed;
  glossy.footprint = shared.footprint;
  glossy.threads = shared.threads;
  glossy.progress = shared.progress;
  glossy.dist = shared.dist;
  return glossy;
}

std::vector<glm::vec3> glossy_vertex_radiance(const mesh::Mesh& mesh, const EnvironmentSampler& environment,
                                              const GlossyReferenceOptions& options, ReferenceReport* report,
                                              std::vector<glm::vec3>* standard_error) {
  ReferenceOptions checked;
  checked.bounces = options.estimator.bounces;
  checked.samples = options.samples;
  check_options(checked);
  ReferenceReport local_report;
  ReferenceReport& rep = report ? *report : local_report;
  rep = ReferenceReport{};

  auto start = std::chrono::steady_clock::now();
  const trace::Scene scene(mesh, trace::SceneOptions{1, true});  // one build thread: see reference.h
  rep.seconds_build = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const GlossyTracer tracer(mesh, scene, environment, options.estimator);
  const auto footprints = mesh::footprints_for(mesh, options.footprint);
  return detail::trace_every_vertex<GlossyWorkspace>(
      mesh.positions, "reference glossy", options.seed, options.samples, options.threads, options.progress, options.dist,
      rep, standard_error, [&](std::uint32_t v, SampleStream& stream, GlossyWorkspace& workspace) {
        const glm::dvec3 to_eye = options.eye - glm::dvec3(mesh.positions[v]);
        const double distance = glm::length(to_eye);
        const glm::dvec3 view = distance > 0.0 ? to_eye / distance : glm::dvec3(mesh.normals[v]);
        if (!footprints) return tracer.vertex_radiance(v, mesh.positions[v], view, options.samples, stream, workspace);
        return detail::footprint_estimate(*footprints, v, options.seed, options.samples,
                                          [&](const glm::vec3& position, std::uint32_t triangle, int paths, SampleStream& run_stream) {
                                            return tracer.vertex_radiance(v, position, view, paths, run_stream, workspace, triangle);
                                          });
      });
}

}  // namespace prt::reference
