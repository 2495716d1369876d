#include "shade/disc_direct.h"

#include <cmath>
#include <functional>

#include <glm/geometric.hpp>

#include "brdf/frame.h"
#include "core/constants.h"
#include "core/error.h"
#include "core/hash.h"
#include "core/parallel.h"
#include "trace/scene.h"
#include "trace/true_surface.h"

namespace prt::shade {

namespace {

int side_of(int samples) {
  if (samples < 1 || samples > 65536) fail_option("sun_samples", " " + std::to_string(samples) + " is out of range 1..65536");
  int k = 1;
  while (k * k < samples) ++k;
  return k;
}

std::vector<glm::dvec3> stratified_directions(const light::Disc& disc, int k) {
  std::vector<glm::dvec3> out;
  out.reserve(static_cast<std::size_t>(k) * k);
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j) out.push_back(light::disc_direction_sample(disc, (i + 0.5) / k, (j + 0.5) / k));
  return out;
}

// For every vertex and disc: calls weight(v, w) for each disc direction w above the tangent plane and
// sums weight x V x L Omega / S into out[v], with V from `scene` (1 without one).
void accumulate(const mesh::Mesh& mesh, const std::vector<light::Disc>& discs, const trace::Scene* scene,
                const DiscShadingOptions& options, const std::function<glm::dvec3(std::size_t, const glm::dvec3&)>& weight,
                std::vector<glm::vec3>& out) {
  const int k = side_of(options.samples);
  out.assign(mesh.positions.size(), glm::vec3(0.0f));
  for (const light::Disc& disc : discs) {
    const std::vector<glm::dvec3> directions = stratified_directions(disc, k);
    const glm::dvec3 scale = disc.radiance() * (disc.solid_angle() / static_cast<double>(directions.size()));
    parallel_for(mesh.positions.size(), 64, options.threads, [&](std::size_t begin, std::size_t end) {
      trace::RayBatch batch(directions.size());
      std::vector<glm::dvec3> w_of(directions.size());
      std::vector<char> below(directions.size());
      for (std::size_t v = begin; v < end; ++v) {
        const glm::dvec3 n(mesh.normals[v]);
        batch.clear();
        std::size_t used = 0;
        const std::uint32_t scramble = options.footprints ? hash_to_u32(options.seed, v, kDiscFootprintSalt) : 0;
        for (std::size_t s = 0; s < directions.size(); ++s) {
          const glm::dvec3& w = directions[s];
          if (!(glm::dot(n, w) > 0.0)) continue;
          w_of[used++] = w;
          if (!scene) continue;
          std::uint32_t triangle = mesh::kNoTriangle;
          const glm::vec3 from = options.footprints ? options.footprints->stratified_point(static_cast<std::uint32_t>(v),
                                                                                            static_cast<std::uint32_t>(s), scramble, &triangle)
                                                    : mesh.positions[v];
          const trace::TrueSurface rule = options.geometric_normals ? trace::TrueSurface{glm::dvec3((*options.geometric_normals)[v])}
                                                                    : trace::true_surface(mesh, triangle);
          below[used - 1] = !rule.admits(w);
          batch.push(scene->offset_origin(from, mesh.normals[v]), glm::vec3(w));
        }
        if (scene && used) scene->occluded(batch);
        glm::dvec3 sum(0.0);
        for (std::size_t s = 0; s < used; ++s)
          if (!scene || !(batch.is_occluded(s) || below[s])) sum += weight(v, w_of[s]);
        out[v] += glm::vec3(sum * scale);
      }
    });
  }
}

void check_size(std::size_t got, const mesh::Mesh& mesh, const char* what) {
  if (got != mesh.positions.size())
    fail(std::string("disc shading: ") + what + " has " + std::to_string(got) + " entries for " +
         std::to_string(mesh.positions.size()) + " vertices");
}

}  // namespace

std::vector<glm::vec3> disc_direct_diffuse(const mesh::Mesh& mesh, const std::vector<glm::vec3>& albedo,
                                           const std::vector<light::Disc>& discs, const trace::Scene* scene,
                                           const DiscShadingOptions& options) {
  check_size(albedo.size(), mesh, "albedo");
  std::vector<glm::vec3> out;
  accumulate(mesh, discs, scene, options,
             [&](std::size_t v, const glm::dvec3& w) {
               return glm::dvec3(albedo[v]) * (kInvPi * glm::dot(glm::dvec3(mesh.normals[v]), w));
             },
             out);
  return out;
}

std::vector<glm::vec3> disc_direct_glossy(const mesh::Mesh& mesh, const brdf::Brdf& surface,
                                          const std::vector<light::Disc>& discs, const std::vector<glm::vec3>& view,
                                          const trace::Scene* scene, const DiscShadingOptions& options) {
  check_size(view.size(), mesh, "view directions");
  std::vector<glm::vec3> out;
  accumulate(mesh, discs, scene, options,
             [&](std::size_t v, const glm::dvec3& w) {
               const glm::dmat3 frame = brdf::shading_frame(glm::dvec3(mesh.normals[v]));
               const glm::dmat3 to_local = glm::transpose(frame);
               return brdf::eval_cosine(surface, glm::normalize(to_local * w), glm::normalize(to_local * glm::dvec3(view[v])));
             },
             out);
  return out;
}

std::vector<float> disc_visibility(const mesh::Mesh& mesh, const light::Disc& disc, const trace::Scene& scene,
                                   const DiscShadingOptions& options) {
  const int k = side_of(options.samples);
  const std::vector<glm::dvec3> directions = stratified_directions(disc, k);
  std::vector<float> out(mesh.positions.size(), 1.0f);
  parallel_for(mesh.positions.size(), 64, options.threads, [&](std::size_t begin, std::size_t end) {
    trace::RayBatch batch(directions.size());
    for (std::size_t v = begin; v < end; ++v) {
      batch.clear();
      for (const glm::dvec3& w : directions)
        if (glm::dot(glm::dvec3(mesh.normals[v]), w) > 0.0)
          batch.push(scene.offset_origin(mesh.positions[v], mesh.normals[v]), glm::vec3(w));
      if (batch.size() == 0) continue;
      scene.occluded(batch);
      out[v] = 1.0f - static_cast<float>(batch.occluded_count()) / static_cast<float>(batch.size());
    }
  });
  return out;
}

}  // namespace prt::shade
