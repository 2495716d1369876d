#include "reference/glossy_estimator.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "brdf/frame.h"
#include "core/error.h"
#include "reference/brdf_sampling.h"
#include "reference/path_loop.h"
#include "sh/sampling.h"
#include "sh/basis.h"
#include "trace/true_surface.h"

namespace prt::reference {

namespace {

constexpr double kTableFraction = 0.9;          // depth-0 band-limited sampling: table vs uniform
constexpr double kBandLimitedUniform = 0.3;     // uniform share of the lobe mixture, band-limited BRDF
constexpr int kTableHeight = 32;                // |rho_BL| table: 2H x H equirect cells


}  // namespace

// A surface point of a path and what its BRDF evaluation needs.
struct PathPoint {
  glm::dvec3 normal{0.0, 1.0, 0.0};
  glm::dmat3 frame{1.0};      // brdf::shading_frame(normal): local -> world
  glm::dvec3 origin{0.0};     // where its rays start
  glm::dvec3 view_local{0.0, 0.0, 1.0};
  double* weights = nullptr;  // band-limited: u_c = B_c^T y(view_local), 3 blocks of bands^2
  trace::TrueSurface surface{};  // the true-surface rule there (none at a mesh vertex)
};

// The true-surface rule (trace/true_surface.h) for a direction w that would be traced (n . w > 0; below
// the tangent plane the band-limited BRDF sees the environment untraced, as glossy PRT does): false
// where w lies below p's triangle, so it carries no light.
static bool admitted(const PathPoint& p, const glm::dvec3& w) {
  return !(glm::dot(p.normal, w) > 0.0) || p.surface.admits(w);
}

struct GlossyWorkspace::Buffers : detail::PathBuffers<PathPoint> {
  std::vector<double> weights;  // kPathsPerWave blocks of 3 bands^2 (band-limited BRDF)
  std::vector<double> start_weights, basis;
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
    fail_option("brdf_bands", " " + std::to_string(options.brdf_bands) + " is out of range 1.." + std::to_string(sh::kMaxBands));
  impl_ = std::make_unique<Impl>(mesh, scene, environment, options);
}

GlossyTracer::~GlossyTracer() = default;

namespace {

// The glossy surface model of the path loop (path_loop.h) for one estimate: the BRDF of Impl, and at
// the vertex being estimated with the band-limited BRDF, the sign-aware table strategy (see the header).
class GlossySurface {
 public:
  using Point = PathPoint;

  GlossySurface(const GlossyTracer::Impl& im, GlossyWorkspace::Buffers& ws, const EnvironmentSampler* table)
      : im_(im), ws_(ws), table_(table), block_(3 * static_cast<std::size_t>(im.coefficients())) {}

  void start_path(std::size_t j, const Point& start, Point& point) {
    point = start;
    point.weights = ws_.weights.data() + block_ * j;
    std::copy(ws_.start_weights.begin(), ws_.start_weights.end(), point.weights);
  }

  bool light_terms(const Point& p, int depth, const glm::dvec3& w, glm::dvec3& rho, double& pdf) {
    const glm::dvec3 local = glm::transpose(p.frame) * w;
    rho = im_.rho(p, local, ws_.basis);
    if (rho == glm::dvec3(0.0) || !admitted(p, w)) return false;
    pdf = strategy_pdf(p, depth, local);
    return true;
  }

  bool sample(const Point& p, int depth, glm::dvec2 u, detail::BsdfSample& s) {
    glm::dvec3 local;
    if (!strategy_sample(p, depth, u, local)) return false;
    s.pdf = strategy_pdf(p, depth, local);
    if (!(s.pdf > 0.0)) return false;
    const glm::dvec3 r = im_.rho(p, local, ws_.basis);
    s.direction = glm::normalize(p.frame * local);
    if (r == glm::dvec3(0.0) || !admitted(p, s.direction)) return false;
    s.weight = r / s.pdf;
    return true;
  }

  bool next_point(const trace::HitResult& hit, const glm::dvec3& direction, Point& next) {
    detail::HitGeometry g;
    if (!detail::hit_geometry(im_.mesh, im_.scene, hit, glm::vec3(direction), g)) return false;
    next.normal = g.normal;
    next.frame = brdf::shading_frame(next.normal);
    next.origin = g.origin;
    next.surface = trace::TrueSurface{g.geometric_normal};
    im_.set_view(next, -direction, ws_.basis);
    return true;
  }

 private:
  // Density of the BRDF strategy at local direction w.
  double strategy_pdf(const Point& p, int depth, const glm::dvec3& w) const {
    if (depth == 0 && table_)
      return table_->has_distribution() ? kTableFraction * table_->pdf(w) + (1.0 - kTableFraction) * sh::kSpherePdf
                                        : sh::kSpherePdf;
    return im_.lobes.pdf(w, p.view_local);
  }

  // A local direction from the BRDF strategy; false if the sample is discarded.
  bool strategy_sample(const Point& p, int depth, glm::dvec2 u, glm::dvec3& w) const {
    if (depth == 0 && table_) {
      if (!table_->has_distribution()) {  // rho_BL vanishes at every table point: sample uniformly
        w = sh::square_to_sphere(u);
        return true;
      }
      if (u.x < kTableFraction) {
        u.x = std::min(u.x / kTableFraction, std::nextafter(1.0, 0.0));
        w = table_->sample(u).direction;
      } else {
        u.x = std::min((u.x - kTableFraction) / (1.0 - kTableFraction), std::nextafter(1.0, 0.0));
        w = sh::square_to_sphere(u);
      }
      return true;
    }
    return im_.lobes.sample(u, p.view_local, w);
  }

  const GlossyTracer::Impl& im_;
  GlossyWorkspace::Buffers& ws_;
  const EnvironmentSampler* table_;
  std::size_t block_;
};

}  // namespace

RadianceEstimate GlossyTracer::vertex_radiance(std::uint32_t vertex, const glm::vec3& position, const glm::dvec3& view,
                                               int paths, SampleStream& stream, GlossyWorkspace& workspace,
                                               std::uint32_t triangle) const {
  const Impl& im = *impl_;
  GlossyWorkspace::Buffers& ws = workspace.buffers();
  const std::size_t block = 3 * static_cast<std::size_t>(im.coefficients());
  ws.weights.resize(block * kPathsPerWave);
  ws.start_weights.resize(block);

  PathPoint start;
  start.normal = glm::normalize(glm::dvec3(im.mesh.normals[vertex]));
  start.frame = brdf::shading_frame(start.normal);
  start.origin = glm::dvec3(im.scene.offset_origin(position, im.mesh.normals[vertex]));
  start.weights = ws.start_weights.data();
  start.surface = trace::true_surface(im.mesh, triangle);
  im.set_view(start, glm::normalize(view), ws.basis);
  std::optional<EnvironmentSampler> table;
  if (im.matrix) table.emplace(im.table_for(start, ws.basis));

  GlossySurface surface(im, ws, table ? &*table : nullptr);
  detail::PathLoop<GlossySurface> loop(surface, im.scene, im.environment, im.options.bounces, stream, ws);
  return loop.run(start, paths);
}

}  // namespace prt::reference
