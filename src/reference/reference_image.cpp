#include "reference/reference_image.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <string>

#include <glm/geometric.hpp>

#include "core/error.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "core/stopwatch.h"
#include "dist/exchange.h"
#include "reference/estimator.h"
#include "reference/vertex_driver.h"
#include "trace/scene.h"

namespace prt::reference {

mesh::Mesh mesh_in_environment_frame(const mesh::Mesh& mesh, const glm::dmat3& environment_rotation,
                                     const glm::dmat3& object_rotation) {
  if (environment_rotation == glm::dmat3(1.0) && object_rotation == glm::dmat3(1.0)) return mesh;
  const mesh::Bounds bounds = mesh::bounds(mesh);
  const glm::dvec3 centre = (glm::dvec3(bounds.lo) + glm::dvec3(bounds.hi)) * 0.5;
  const glm::dmat3 to_environment = glm::transpose(environment_rotation);  // R_e^-1
  const glm::dmat3 normal_rotation = to_environment * object_rotation;
  mesh::Mesh out = mesh;
  for (std::size_t v = 0; v < out.positions.size(); ++v) {
    const glm::dvec3 world = centre + object_rotation * (glm::dvec3(mesh.positions[v]) - centre);
    out.positions[v] = glm::vec3(to_environment * world);
  }
  for (std::size_t v = 0; v < out.normals.size(); ++v)
    out.normals[v] = glm::vec3(glm::normalize(normal_rotation * glm::dvec3(mesh.normals[v])));
  return out;
}

namespace {

// What every row of one render reads.
struct RowInputs {
  const camera::ViewMatrices& view;
  glm::dmat3 to_environment;  // camera frame -> the environment's frame
  const light::Environment& behind;
  const trace::Scene& scene;
  const PathTracer& tracer;
  const ImageOptions& options;
};

// Per-thread buffers of the row loop.
struct RowScratch {
  explicit RowScratch(std::size_t width) : primary(width), directions(width) {}
  PathWorkspace workspace;
  trace::RayBatch primary;
  std::vector<glm::dvec3> directions;
};

struct RowCounts {
  std::uint64_t rays = 0, paths = 0;
};

// Row `row` (0 at the top) of the image: its primary rays traced in one batch, then each covered pixel's
// outgoing radiance estimated (seeded by the pixel index), into out's radiance, coverage and standard error.
RowCounts render_row(const RowInputs& in, std::size_t row, RowScratch& scratch, ReferenceImage& out) {
  const int y = static_cast<int>(row), width = in.options.width, height = in.options.height;
  const ReferenceOptions& reference = in.options.reference;
  RowCounts counts;
  scratch.primary.clear();
  for (int x = 0; x < width; ++x) {
    const camera::PixelRay ray = camera::pixel_ray(in.view, x, y, width, height);
    scratch.directions[x] = in.to_environment * ray.direction;
    scratch.primary.push(glm::vec3(in.to_environment * ray.origin), glm::vec3(scratch.directions[x]));
  }
  in.scene.intersect(scratch.primary);
  counts.rays += static_cast<std::uint64_t>(width);
  for (int x = 0; x < width; ++x) {
    const std::size_t pixel = row * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
    const trace::HitResult hit = scratch.primary.hit(static_cast<std::size_t>(x));
    glm::dvec3 value(0.0);
    if (!hit.hit()) {
      if (!in.options.black_background) value = in.behind.radiance(scratch.directions[x]);
    } else {
      out.covered[pixel] = 1;
      SurfacePoint point;
      if (in.tracer.hit_point(hit, glm::vec3(scratch.directions[x]), point)) {
        SampleStream stream(reference.seed, pixel);
        const RadianceEstimate estimate =
            in.tracer.outgoing_radiance(point, reference.samples, stream, scratch.workspace);
        value = estimate.value;
        out.standard_error[pixel] = glm::vec3(estimate.standard_error);
        counts.rays += estimate.rays;
        counts.paths += static_cast<std::uint64_t>(reference.samples);
      }
    }
    for (int c = 0; c < 3; ++c) out.radiance.at(x, y, c) = static_cast<float>(value[c]);
  }
  return counts;
}

// The noise figure over the covered pixels, as the vertex reference computes it (detail::summarise_noise).
void summarise_pixel_noise(ReferenceImage& out) {
  std::vector<glm::vec3> radiance;
  std::vector<glm::dvec3> error;
  for (std::size_t p = 0; p < out.covered.size(); ++p) {
    if (!out.covered[p]) continue;
    const float* rgb = &out.radiance.pixels[3 * p];
    radiance.emplace_back(rgb[0], rgb[1], rgb[2]);
    error.emplace_back(out.standard_error[p]);
  }
  detail::summarise_noise(radiance, error, out.report, nullptr);
}

}  // namespace

ReferenceImage render_image(const mesh::Mesh& original_mesh, const EnvironmentSampler& environment,
                            const ImageOptions& options, const light::Environment* background) {
  check_options(options.reference);
  if (options.width < 1 || options.height < 1)
    fail_option("size", ": expected at least 1x1 pixels, got " + std::to_string(options.width) + "x" +
         std::to_string(options.height));
  if (original_mesh.indices.empty()) fail("the mesh has no triangles to render");
  const int width = options.width, height = options.height;
  const std::size_t pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);

  ReferenceImage out;
  ReferenceReport& rep = out.report;
  const camera::ViewMatrices view =
      camera::orbit_view(options.camera, mesh::bounds(original_mesh), width, height, options.object_rotation);
  const mesh::Mesh mesh =
      mesh_in_environment_frame(original_mesh, options.environment_rotation, options.object_rotation);
  const std::vector<glm::vec3> albedo = reference_albedo(mesh, options.reference.albedo);

  auto start = std::chrono::steady_clock::now();
  // One build thread: the BVH, and so closest-hit ties on shared edges, cannot depend on --threads.
  const trace::Scene scene(mesh, trace::SceneOptions{1, true});
  rep.seconds_build = seconds_since(start);
  const PathTracer tracer(mesh, albedo, scene, environment, EstimatorOptions{options.reference.bounces});
  const RowInputs inputs{view, glm::transpose(options.environment_rotation),
                         background ? *background : environment.environment(), scene, tracer, options};

  out.radiance = image::Image(width, height, 3);
  out.covered.assign(pixels, 0);
  out.standard_error.assign(pixels, glm::vec3(0.0f));
  std::atomic<std::uint64_t> rays{0}, paths{0};
  Progress progress("reference", "rows", static_cast<std::size_t>(height), options.reference.progress);
  start = std::chrono::steady_clock::now();
  // Distributed: each rank renders its share of the rows (top to bottom), rank 0 gathers them.
  const dist::Context& ranks = dist::or_single(options.reference.dist);
  const dist::Range share = dist::my_range(ranks, static_cast<std::size_t>(height));
  parallel_for(share.size(), 1, options.reference.threads, [&](std::size_t chunk_begin, std::size_t chunk_end) {
    RowScratch scratch(static_cast<std::size_t>(width));
    RowCounts chunk;
    for (std::size_t row = share.begin + chunk_begin; row < share.begin + chunk_end; ++row) {
      const RowCounts counts = render_row(inputs, row, scratch, out);
      chunk.rays += counts.rays;
      chunk.paths += counts.paths;
    }
    rays += chunk.rays;
    paths += chunk.paths;
    progress.advance((chunk_end - chunk_begin) * static_cast<std::size_t>(ranks.size()));  // equal shares
  });
  progress.finish();
  dist::gather_items(ranks, out.radiance.pixels, static_cast<std::size_t>(width) * 3);
  dist::gather_items(ranks, out.covered, static_cast<std::size_t>(width));
  dist::gather_items(ranks, out.standard_error, static_cast<std::size_t>(width));
  rep.seconds_trace = seconds_since(start);
  rep.rays = ranks.sum(rays.load());
  rep.paths = ranks.sum(paths.load());
  summarise_pixel_noise(out);
  return out;
}

}  // namespace prt::reference
