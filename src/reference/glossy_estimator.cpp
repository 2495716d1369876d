#include "reference/glossy_estimator.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "brdf/frame.h"
#include "core/error.h"
#include "reference/brdf_sampling.h"
#include "sh/basis.h"

namespace prt::reference {

namespace {

constexpr double kUniformSpherePdf = 0.25 / M_PI;
constexpr double kTableFraction = 0.9;          // depth-0 band-limited sampling: table vs uniform
constexpr double kBandLimitedUniform = 0.3;     // uniform share of the lobe mixture, band-limited BRDF
constexpr int kTableHeight = 32;                // |rho_BL| table: 2H x H equirect cells

double power_heuristic(double own, double other) {
  const double a = own * own, b = other * other;
  return a + b > 0.0 ? a / (a + b) : 0.0;
}

glm::vec3 to_float(const glm::dvec3& v) { return glm::vec3(v); }

}  // namespace

// A surface point of a path and what its BRDF evaluation needs.
struct PathPoint {
  glm::dvec3 normal{0.0, 1.0, 0.0};
  glm::dmat3 frame{1.0};      // brdf::shading_frame(normal): local -> world
  glm::dvec3 origin{0.0};     // where its rays start
  glm::dvec3 view_local{0.0, 0.0, 1.0};
  double* weights = nullptr;  // band-limited: u_c = B_c^T y(view_local), 3 blocks of bands^2
};

struct GlossyWorkspace::Buffers {
  struct Path {
    PathPoint point;
    glm::dvec3 throughput{1.0};
    glm::dvec3 value{0.0};
    std::uint32_t index = 0;
    int depth = 0;
  };
  trace::RayBatch shadow{kPathsPerWave};
  trace::RayBatch bounce{kPathsPerWave};
  std::vector<Path> paths = std::vector<Path>(kPathsPerWave);
  std::vector<double> weights;  // kPathsPerWave blocks of 3 bands^2 (band-limited BRDF)
  std::vector<double> start_weights, basis;
  std::vector<std::uint32_t> active, next_active;
  std::vector<glm::dvec3> shadow_contribution = std::vector<glm::dvec3>(kPathsPerWave);
  std::vector<std::uint32_t> shadow_owner = std::vector<std::uint32_t>(kPathsPerWave);
  std::vector<std::uint32_t> bounce_owner = std::vector<std::uint32_t>(kPathsPerWave);
  std::vector<glm::dvec3> bounce_direction = std::vector<glm::dvec3>(kPathsPerWave);
  std::vector<glm::dvec3> bounce_weight = std::vector<glm::dvec3>(kPathsPerWave);
  std::vector<double> bounce_pdf = std::vector<double>(kPathsPerWave);
};

GlossyWorkspace::GlossyWorkspace() : buffers_(std::make_unique<Buffers>()) {}
GlossyWorkspace::~GlossyWorkspace() = default;

struct GlossyTracer::Impl {
  const mesh::Mesh& mesh;
  const trace::Scene& scene;
  const EnvironmentSampler& environment;
  GlossyEstimatorOptions options;
  std::optional<brdf::BrdfMatrix> matrix;  // band-limited BRDF
  LobeSampler lobes;

  Impl(const mesh::Mesh& m, const trace::Scene& s, const EnvironmentSampler& e, const GlossyEstimatorOptions& o)
      : mesh(m), scene(s), environment(e), options(o), lobes(o.brdf, o.brdf_bands > 0 ? kBandLimitedUniform : 0.0) {
    if (o.brdf_bands > 0) matrix = brdf::project(o.brdf, o.brdf_bands);
  }

  int coefficients() const { return matrix ? matrix->coefficients() : 0; }

  // Sets the view of `point` and, for the band-limited BRDF, its weights u_c = B_c^T y(view).
  void set_view(PathPoint& point, const glm::dvec3& view_world, std::vector<double>& basis) const {
    point.view_local = glm::transpose(point.frame) * view_world;
    if (!matrix) return;
    const int n = coefficients();
    basis.resize(static_cast<std::size_t>(n));
    sh::eval(matrix->bands, point.view_local, basis.data());
    for (int c = 0; c < 3; ++c) {
      const double* b = matrix->for_colour(c);
      double* u = point.weights + static_cast<std::size_t>(c) * n;
      std::fill(u, u + n, 0.0);
      for (int k = 0; k < n; ++k) {
        if (basis[k] == 0.0) continue;
        const double* row = b + static_cast<std::size_t>(k) * n;
        for (int j = 0; j < n; ++j) u[j] += basis[k] * row[j];
      }
    }
  }

  // rho(w_local, view) per channel (see the header).
  glm::dvec3 rho(const PathPoint& point, const glm::dvec3& w_local, std::vector<double>& basis) const {
    if (!matrix) return brdf::eval_cosine(options.brdf, w_local, point.view_local);
    const int n = coefficients();
    basis.resize(static_cast<std::size_t>(n));
    sh::eval(matrix->bands, w_local, basis.data());
    glm::dvec3 out(0.0);
    for (int c = 0; c < 3; ++c) {
      const double* u = point.weights + static_cast<std::size_t>(c) * n;
      double sum = 0.0;
      for (int j = 0; j < n; ++j) sum += u[j] * basis[j];
      out[c] = sum;
    }
    return out;
  }

  // The sign-aware table of |rho_BL(., view)| over the local sphere for the vertex being estimated.
  EnvironmentSampler table_for(const PathPoint& point, std::vector<double>& basis) const {
    light::Environment table;
    table.layout = light::Environment::Layout::equirect;
    table.equirect = image::Image(2 * kTableHeight, kTableHeight, 3);
    for (int y = 0; y < kTableHeight; ++y)
      for (int x = 0; x < 2 * kTableHeight; ++x) {
        const glm::dvec3 w = light::equirect_direction((x + 0.5) / (2 * kTableHeight), (y + 0.5) / kTableHeight);
        const double magnitude = sampling_magnitude(rho(point, w, basis));
        for (int c = 0; c < 3; ++c) table.equirect.at(x, y, c) = static_cast<float>(magnitude);
      }
    return EnvironmentSampler(std::move(table));
  }
};

GlossyTracer::GlossyTracer(const mesh::Mesh& mesh, const trace::Scene& scene, const EnvironmentSampler& environment,
                           const GlossyEstimatorOptions& options) {
  if (options.brdf.empty()) fail("glossy reference: empty BRDF");
  if (options.brdf_bands < 0 || options.brdf_bands > sh::kMaxBands)
    fail("--brdf-bands " + std::to_string(options.brdf_bands) + " is out of range 1.." + std::to_string(sh::kMaxBands));
  impl_ = std::make_unique<Impl>(mesh, scene, environment, options);
}

GlossyTracer::~GlossyTracer() = default;

RadianceEstimate GlossyTracer::vertex_radiance(std::uint32_t vertex, const glm::dvec3& view, int paths, SampleStream& stream,
                                               GlossyWorkspace& workspace) const {
  const Impl& im = *impl_;
  GlossyWorkspace::Buffers& ws = workspace.buffers();
  sh::Rng& rng = stream.rng();
  const bool light_sampling = im.environment.has_distribution();
  const bool band_limited = im.matrix.has_value();
  const std::size_t block = 3 * static_cast<std::size_t>(im.coefficients());
  ws.weights.resize(block * kPathsPerWave);
  ws.start_weights.resize(block);

  PathPoint start;
  start.normal = glm::normalize(glm::dvec3(im.mesh.normals[vertex]));
  start.frame = brdf::shading_frame(start.normal);
  start.origin = glm::dvec3(im.scene.offset_origin(im.mesh.positions[vertex], im.mesh.normals[vertex]));
  start.weights = ws.start_weights.data();
  im.set_view(start, glm::normalize(view), ws.basis);
  std::optional<EnvironmentSampler> table;
  if (band_limited) table.emplace(im.table_for(start, ws.basis));

  // Density of the BRDF strategy of `path` at local direction w.
  auto strategy_pdf = [&](const GlossyWorkspace::Buffers::Path& path, const glm::dvec3& w) {
    if (path.depth == 0 && table)
      return table->has_distribution() ? kTableFraction * table->pdf(w) + (1.0 - kTableFraction) * kUniformSpherePdf
                                       : kUniformSpherePdf;
    return im.lobes.pdf(w, path.point.view_local);
  };
  // A local direction from the BRDF strategy of `path`; false if the sample is discarded.
  auto strategy_sample = [&](const GlossyWorkspace::Buffers::Path& path, glm::dvec2 u, glm::dvec3& w) {
    if (path.depth == 0 && table) {
      if (!table->has_distribution()) {  // rho_BL vanishes at every table point: sample uniformly
        w = sh::square_to_sphere(u);
        return true;
      }
      if (u.x < kTableFraction) {
        u.x = std::min(u.x / kTableFraction, std::nextafter(1.0, 0.0));
        w = table->sample(u).direction;
      } else {
        u.x = std::min((u.x - kTableFraction) / (1.0 - kTableFraction), std::nextafter(1.0, 0.0));
        w = sh::square_to_sphere(u);
      }
      return true;
    }
    return im.lobes.sample(u, path.point.view_local, w);
  };

  glm::dvec3 sum(0.0), sum_sq(0.0);
  std::uint64_t rays = 0;
  for (int first = 0; first < paths; first += kPathsPerWave) {
    const int wave = std::min(kPathsPerWave, paths - first);
    ws.active.clear();
    for (int j = 0; j < wave; ++j) {
      GlossyWorkspace::Buffers::Path& path = ws.paths[j];
      path = GlossyWorkspace::Buffers::Path{start, glm::dvec3(1.0), glm::dvec3(0.0), static_cast<std::uint32_t>(first + j), 0};
      path.point.weights = ws.weights.data() + block * j;
      std::copy(ws.start_weights.begin(), ws.start_weights.end(), path.point.weights);
      ws.active.push_back(static_cast<std::uint32_t>(j));
    }
    for (int depth = 0; !ws.active.empty(); ++depth) {
      const bool last = depth >= im.options.bounces;
      ws.shadow.clear();
      ws.bounce.clear();
      for (std::uint32_t a : ws.active) {
        GlossyWorkspace::Buffers::Path& path = ws.paths[a];
        const PathPoint& point = path.point;
        const glm::vec3 origin = to_float(point.origin);
        // 1. Environment sample (next-event estimation).
        if (light_sampling) {
          const EnvironmentSampler::Sample s = im.environment.sample(sh::sobol_2d(path.index, stream.dimension_seed(depth, 0)));
          const glm::dvec3 local = glm::transpose(point.frame) * s.direction;
          const glm::dvec3 r = im.rho(point, local, ws.basis);
          if (r != glm::dvec3(0.0)) {
            const glm::dvec3 contribution = path.throughput * r * im.environment.radiance(s.direction) *
                                            (power_heuristic(s.pdf, strategy_pdf(path, local)) / s.pdf);
            if (glm::dot(point.normal, s.direction) <= 0.0) {
              path.value += contribution;  // below the tangent plane: not traced (see the header)
            } else if (contribution != glm::dvec3(0.0)) {
              const std::size_t k = ws.shadow.push(origin, to_float(s.direction));
              ws.shadow_contribution[k] = contribution;
              ws.shadow_owner[k] = a;
            }
          }
        }
        // 2. BRDF sample.
        glm::dvec3 local;
        if (!strategy_sample(path, sh::sobol_2d(path.index, stream.dimension_seed(depth, 1)), local)) continue;
        const double pdf = strategy_pdf(path, local);
        if (!(pdf > 0.0)) continue;
        const glm::dvec3 r = im.rho(point, local, ws.basis);
        if (r == glm::dvec3(0.0)) continue;
        const glm::dvec3 direction = glm::normalize(point.frame * local);
        const glm::dvec3 weight = path.throughput * r / pdf;
        if (glm::dot(point.normal, direction) <= 0.0) {
          const double light_pdf = light_sampling ? im.environment.pdf(direction) : 0.0;
          path.value += weight * im.environment.radiance(direction) * power_heuristic(pdf, light_pdf);
          continue;
        }
        const std::size_t k = ws.bounce.push(origin, to_float(direction));
        ws.bounce_owner[k] = a;
        ws.bounce_direction[k] = direction;
        ws.bounce_weight[k] = weight;
        ws.bounce_pdf[k] = pdf;
      }

      if (!ws.shadow.empty()) {
        im.scene.occluded(ws.shadow);
        rays += ws.shadow.size();
        for (std::size_t k = 0; k < ws.shadow.size(); ++k)
          if (!ws.shadow.is_occluded(k)) ws.paths[ws.shadow_owner[k]].value += ws.shadow_contribution[k];
      }
      rays += ws.bounce.size();
      ws.next_active.clear();
      if (!ws.bounce.empty()) {
        if (last) im.scene.occluded(ws.bounce);
        else im.scene.intersect(ws.bounce);
      }
      for (std::size_t k = 0; k < ws.bounce.size(); ++k) {
        GlossyWorkspace::Buffers::Path& path = ws.paths[ws.bounce_owner[k]];
        const glm::dvec3& direction = ws.bounce_direction[k];
        const bool escaped = last ? !ws.bounce.is_occluded(k) : !ws.bounce.hit(k).hit();
        if (escaped) {
          const double light_pdf = light_sampling ? im.environment.pdf(direction) : 0.0;
          path.value += ws.bounce_weight[k] * im.environment.radiance(direction) * power_heuristic(ws.bounce_pdf[k], light_pdf);
          continue;
        }
        if (last) continue;
        // A front-face hit continues the path there (position, normal interpolated as estimator.h).
        const trace::HitResult hit = ws.bounce.hit(k);
        const std::uint32_t* tri = im.mesh.indices.data() + 3 * static_cast<std::size_t>(hit.prim_id);
        const glm::vec3& p0 = im.mesh.positions[tri[0]];
        const glm::vec3 face_normal = glm::cross(im.mesh.positions[tri[1]] - p0, im.mesh.positions[tri[2]] - p0);
        if (glm::dot(face_normal, to_float(direction)) >= 0.0f) continue;
        const double u = hit.u, v = hit.v, w = 1.0 - u - v;
        const glm::dvec3 position = w * glm::dvec3(p0) + u * glm::dvec3(im.mesh.positions[tri[1]]) +
                                    v * glm::dvec3(im.mesh.positions[tri[2]]);
        const glm::dvec3 ng = glm::normalize(glm::dvec3(face_normal));
        const glm::dvec3 n = w * glm::dvec3(im.mesh.normals[tri[0]]) + u * glm::dvec3(im.mesh.normals[tri[1]]) +
                             v * glm::dvec3(im.mesh.normals[tri[2]]);
        const double length = glm::length(n);
        glm::dvec3 throughput = ws.bounce_weight[k];
        if (depth + 1 >= kRouletteDepth) {
          const double survive = std::min(1.0, std::max({std::abs(throughput.x), std::abs(throughput.y), std::abs(throughput.z)}));
          if (!(rng.next_double() < survive)) continue;
          throughput /= survive;
        }
        path.point.normal = length > 1e-12 ? n / length : ng;
        path.point.frame = brdf::shading_frame(path.point.normal);
        path.point.origin = position + ng * static_cast<double>(im.scene.ray_offset());
        im.set_view(path.point, -direction, ws.basis);
        path.throughput = throughput;
        path.depth = depth + 1;
        ws.next_active.push_back(ws.bounce_owner[k]);
      }
      std::swap(ws.active, ws.next_active);
    }
    for (int j = 0; j < wave; ++j) {
      sum += ws.paths[j].value;
      sum_sq += ws.paths[j].value * ws.paths[j].value;
    }
  }

  return mean_estimate(sum, sum_sq, paths, rays);
}

}  // namespace prt::reference
