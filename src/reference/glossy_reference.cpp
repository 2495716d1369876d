// The per-vertex driver of the glossy reference (glossy_estimator.h).
#include <chrono>

#include <glm/geometric.hpp>

#include "reference/glossy_estimator.h"
#include "reference/vertex_driver.h"

namespace prt::reference {

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
  return detail::trace_every_vertex<GlossyWorkspace>(
      mesh.positions, "reference glossy", options.seed, options.samples, options.threads, options.progress, options.dist,
      rep, standard_error, [&](std::uint32_t v, SampleStream& stream, GlossyWorkspace& workspace) {
        const glm::dvec3 to_eye = options.eye - glm::dvec3(mesh.positions[v]);
        const double distance = glm::length(to_eye);
        const glm::dvec3 view = distance > 0.0 ? to_eye / distance : glm::dvec3(mesh.normals[v]);
        return tracer.vertex_radiance(v, view, options.samples, stream, workspace);
      });
}

}  // namespace prt::reference
