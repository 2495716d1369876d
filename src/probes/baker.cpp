#include "probes/baker.h"

#include <atomic>
#include <chrono>
#include <cmath>
#include <ctime>
#include <memory>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>
#include <nlohmann/json.hpp>

#include "bake/bake.h"
#include "core/constants.h"
#include "core/error.h"
#include "core/memory_check.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "core/stopwatch.h"
#include "dist/exchange.h"
#include "light/environment.h"
#include "light/projection.h"
#include "probes/pilot.h"
#include "probes/surface.h"
#include "sh/basis.h"
#include "sh/rotation.h"
#include "sh/sampling.h"
#include "trace/scene.h"

namespace prt::probes {

namespace {

double process_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

std::string parameters_json(const ProbeBakeOptions& o, const SceneLight& light, bool mesh_albedo) {
  nlohmann::ordered_json j;
  j["tool"] = "prt 0.1.0";
  j["bands"] = o.bands;
  j["rays"] = o.rays;
  j["bounces"] = o.bounces;
  j["surface_samples"] = o.surface_samples;
  j["sun_samples"] = o.sun_samples;
  j["seed"] = o.seed;
  j["max_backface_fraction"] = o.max_backface_fraction;
  j["ray_set"] = "owen-scrambled sobol on the sphere, per-probe hashed rotation";
  if (mesh_albedo) j["albedo"] = "mesh";
  else j["albedo"] = {o.albedo.r, o.albedo.g, o.albedo.b};
  j["environment"] = light.environment ? light.environment->source : std::string("none (black)");
  if (light.sun)
    j["sun"] = {{"direction", {light.sun->direction.x, light.sun->direction.y, light.sun->direction.z}},
                {"irradiance", {light.sun->irradiance.x, light.sun->irradiance.y, light.sun->irradiance.z}},
                {"angular_radius_degrees", light.sun->angular_radius * 180.0 / kPi}};
  j["emission"] = !light.emission.empty();
  if (o.transfer_bands > 0) j["transfer_bands"] = o.transfer_bands;
  return j.dump();
}

}  // namespace

std::uint64_t estimated_bytes(std::uint64_t probe_count, const ProbeBakeOptions& o) {
  const std::uint64_t n = std::uint64_t(o.bands) * std::uint64_t(o.bands);
  const std::uint64_t ne = std::uint64_t(o.transfer_bands) * std::uint64_t(o.transfer_bands);
  // dvec3 + vec3 positions, valid, back-face fraction; RGB float coefficients; 3 x n x ne transfer and n RGB bias.
  const std::uint64_t per_probe = 24 + 12 + 1 + 4 + 12 * n + (ne > 0 ? 4 * 3 * n * ne + 12 * n : 0);
  return saturating_product(saturating_product(probe_count, per_probe), 2);
}

void check_options(const ProbeBakeOptions& o) {
  if (o.bands < 1 || o.bands > 16) fail_option("bands", " " + std::to_string(o.bands) + " is out of range 1..16");
  if (o.rays < 1 || o.rays > (1 << 20)) fail_option("rays", " " + std::to_string(o.rays) + " is out of range 1..1048576");
  if (static_cast<double>(o.rays) * o.bands * o.bands > static_cast<double>(1 << 26))
    fail_option("rays", " x bands^2 is too large (more than 2^26 basis values)");
  if (o.bounces < 0 || o.bounces > 64) fail_option("bounces", " " + std::to_string(o.bounces) + " is out of range 0..64");
  if (o.surface_samples < 1 || o.surface_samples > 65536)
    fail_option("surface_samples", " " + std::to_string(o.surface_samples) + " is out of range 1..65536");
  if (o.sun_samples < 1 || o.sun_samples > 4096) fail_option("sun_samples", " " + std::to_string(o.sun_samples) + " is out of range 1..4096");
  if (!(o.max_backface_fraction >= 0.0 && o.max_backface_fraction <= 1.0)) fail_option("max_backface_fraction", " must lie in [0, 1]");
  if (o.transfer_bands < 0 || o.transfer_bands > 8) fail_option("transfer_bands", " " + std::to_string(o.transfer_bands) + " is out of range 1..8");
  for (int c = 0; c < 3; ++c)
    if (!(o.albedo[c] >= 0.0f && o.albedo[c] <= 1.0f)) fail_option("albedo", " components must lie in [0, 1]");
}

namespace {

// A probe's pilot (probes/pilot.h) uses an independent Sobol set.

// Everything the probe loop reads, prepared once.
struct ProbeInputs {
  const trace::Scene* scene = nullptr;
  const mesh::Mesh* mesh = nullptr;
  const SceneLight* light = nullptr;
  const ProbeBakeOptions* options = nullptr;
  const light::Environment* environment = nullptr;  // the lookup copy, or null without an environment
  std::vector<glm::vec3> corner_radiance;            // R_K at each triangle's corners, triangle-major
  std::vector<glm::vec3> directions;                 // the S ray directions before a probe's rotation
  std::vector<float> basis;                          // S x bands^2, Y at each direction
  std::vector<glm::vec3> pilot_directions;           // kPilotRays directions on the sphere
  sh::RgbCoefficients env_sh, sun_sh;                // exact projections, probe bands
  // transfer (transfer_bands > 0)
  transfer::TransferData vertex_transfer;
  std::vector<glm::vec3> bias_radiance;
  int channels = 0;
};

// Per-probe sums in the probe's rotated frame.
struct ProbeSums {
  std::vector<glm::dvec3> radiance, bias;  // bands^2 each
  std::vector<double> transfer;            // channels x bands^2 x transfer_bands^2
  std::size_t backfaces = 0;
  double env_share = 0.0;  // the share of c_env the control variate adds (1 or 0)
  double sun_visible = 0.0;
};

// Scratch of one parallel_for chunk: traces and sums probes one at a time.
class ProbeTracer {
 public:
  explicit ProbeTracer(const ProbeInputs& in)
      : in_(in), o_(*in.options), n_(o_.bands * o_.bands), ne_(o_.transfer_bands * o_.transfer_bands),
        batch_(std::min<std::size_t>(in.directions.size(), trace::kDefaultBatchCapacity)),
        sun_batch_(static_cast<std::size_t>(std::max(o_.sun_samples, kPilotRays))), batch_sum_(n_),
        env_basis_(static_cast<std::size_t>(std::max(ne_, 1))) {
    sums_.radiance.resize(n_);
    sums_.bias.resize(n_);
    sums_.transfer.resize(static_cast<std::size_t>(in.channels) * n_ * ne_);
  }

  std::uint64_t traced() const { return traced_; }

  // Traces probe p and writes its results into `out`.
  void bake(std::size_t p, const glm::vec3& origin, ProbeSet& out) {
    const glm::dmat3 rotation = probe_rotation(o_.seed, p);
    std::fill(sums_.radiance.begin(), sums_.radiance.end(), glm::dvec3(0.0));
    std::fill(sums_.bias.begin(), sums_.bias.end(), glm::dvec3(0.0));
    std::fill(sums_.transfer.begin(), sums_.transfer.end(), 0.0);
    sums_.backfaces = 0;
    const bool plain = mostly_blocked(p, origin);
    sums_.env_share = plain ? 0.0 : 1.0;
    const glm::mat3 rotation_f(rotation);
    const std::size_t samples = in_.directions.size();
    for (std::size_t first = 0; first < samples; first += batch_.capacity()) {
      const std::size_t count = std::min(batch_.capacity(), samples - first);
      batch_.clear();
      for (std::size_t s = first; s < first + count; ++s) batch_.push(origin, rotation_f * in_.directions[s]);
      in_.scene->intersect(batch_);
      traced_ += count;
      // The random reads of the hit triangles' corner radiance were most of this pass's cost beyond
      // Embree (cache misses, measured): prefetch them all before the sums read them.
      batch_.hit_count(in_.corner_radiance.data(), 3 * sizeof(glm::vec3));
      sum_batch(first, count, plain);
    }
    sums_.sun_visible = in_.light->sun ? sun_visibility(p, origin) : 0.0;
    store(p, rotation, out);
  }

 private:
  // Uniform random rotation from three hashed numbers (Shoemake, "Uniform random rotations", GGems III).
  static glm::dmat3 probe_rotation(std::uint32_t seed, std::uint64_t probe, std::uint32_t salt = 0) {
    const double u1 = hash_to_unit(seed, probe, salt + 1), u2 = hash_to_unit(seed, probe, salt + 2),
                 u3 = hash_to_unit(seed, probe, salt + 3);
    const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
    const glm::dquat q(b * std::cos(2.0 * kPi * u3), a * std::sin(2.0 * kPi * u2), a * std::cos(2.0 * kPi * u2),
                       b * std::sin(2.0 * kPi * u3));
    return glm::mat3_cast(glm::normalize(q));
  }

  // The pilot: true if more than half of kPilotRays independent rays from the probe are blocked.
  bool mostly_blocked(std::size_t p, const glm::vec3& origin) {
    const glm::mat3 rotation(probe_rotation(o_.seed, p, kPilotSalt));
    sun_batch_.clear();
    for (const glm::vec3& d : in_.pilot_directions) sun_batch_.push(origin, rotation * d);
    in_.scene->occluded(sun_batch_);
    traced_ += sun_batch_.size();
    return 2 * sun_batch_.occluded_count() > sun_batch_.size();
  }

  // Adds one batch's rays to the sums: with the control variate (plain false) the hit rays' L_hit - L_env;
  // with the plain estimator every ray's L_in.
  void sum_batch(std::size_t first, std::size_t count, bool plain) {
    std::fill(batch_sum_.begin(), batch_sum_.end(), glm::vec3(0.0f));
    for (std::size_t i = 0; i < count; ++i) {
      const glm::vec3 dir = batch_.direction(i);
      const float* y = in_.basis.data() + (first + i) * n_;
      if (!batch_.is_hit(i)) {
        if (plain && in_.environment) add_scaled(batch_sum_, glm::vec3(in_.environment->radiance_float(dir)), y);
        continue;
      }
      const trace::HitResult hit = batch_.hit(i);
      const bool front = batch_.is_front_hit(i);
      glm::vec3 value(0.0f);
      if (!plain && in_.environment) value = -in_.environment->radiance_float(dir);
      if (front) {
        const glm::vec3* corner = in_.corner_radiance.data() + 3 * static_cast<std::size_t>(hit.prim_id);
        value += (1.0f - hit.u - hit.v) * corner[0] + hit.u * corner[1] + hit.v * corner[2];
      } else {
        ++sums_.backfaces;
      }
      add_scaled(batch_sum_, value, y);
      if (ne_ > 0) sum_transfer(hit, front, dir, y);
    }
    for (int k = 0; k < n_; ++k) sums_.radiance[k] += glm::dvec3(batch_sum_[k]);
  }

  void add_scaled(std::vector<glm::vec3>& sum, const glm::vec3& value, const float* y) const {
    for (int k = 0; k < n_; ++k) sum[k] += value * y[k];
  }

  // The transfer matrix and bias terms of one hit ray (baker.h, TRANSFER).
  void sum_transfer(const trace::HitResult& hit, bool front, const glm::vec3& dir, const float* y) {
    const std::uint32_t* tri = in_.mesh->indices.data() + 3 * static_cast<std::size_t>(hit.prim_id);
    sh::eval(o_.transfer_bands, glm::dvec3(dir), env_basis_.data());
    const float w0 = 1.0f - hit.u - hit.v;
    const std::size_t stride = static_cast<std::size_t>(in_.channels) * ne_;  // per vertex in vertex_transfer
    const std::vector<float>& t = in_.vertex_transfer.values;
    for (int c = 0; c < in_.channels; ++c) {
      double* m = sums_.transfer.data() + static_cast<std::size_t>(c) * n_ * ne_;
      for (int j = 0; j < ne_; ++j) {
        double g = -env_basis_[j];
        if (front) {
          const std::size_t offset = static_cast<std::size_t>(c) * ne_ + j;
          g += w0 * t[tri[0] * stride + offset] + hit.u * t[tri[1] * stride + offset] + hit.v * t[tri[2] * stride + offset];
        }
        for (int k = 0; k < n_; ++k) m[static_cast<std::size_t>(k) * ne_ + j] += y[k] * g;
      }
    }
    if (!front) return;
    const glm::dvec3 bias((1.0f - hit.u - hit.v) * in_.bias_radiance[tri[0]] + hit.u * in_.bias_radiance[tri[1]] +
                          hit.v * in_.bias_radiance[tri[2]]);
    for (int k = 0; k < n_; ++k) sums_.bias[k] += bias * static_cast<double>(y[k]);
  }

  // The unoccluded fraction of sun_samples stratified shadow rays toward the sun's disc.
  double sun_visibility(std::size_t p, const glm::vec3& origin) {
    const std::uint32_t scramble = hash_to_u32(o_.seed, p, 0x5u);
    sun_batch_.clear();
    for (int k = 0; k < o_.sun_samples; ++k) {
      const glm::dvec2 u = sh::sobol_2d(static_cast<std::uint32_t>(k), scramble);
      sun_batch_.push(origin, glm::vec3(sun_direction_sample(*in_.light->sun, u.x, u.y)));
    }
    in_.scene->occluded(sun_batch_);
    traced_ += sun_batch_.size();
    return 1.0 - static_cast<double>(sun_batch_.occluded_count()) / o_.sun_samples;
  }

  // Rotates `local` (n values per channel, scaled by `weight`) to the world into `world`.
  void rotate(const sh::Rotation& rot, const double* local, std::size_t stride, double weight, double* world) {
    column_.resize(n_);
    for (int k = 0; k < n_; ++k) column_[k] = local[static_cast<std::size_t>(k) * stride] * weight;
    rot.apply(column_.data(), world);
  }

  // Rotates the sums to the world, adds the exact parts and writes probe p.
  void store(std::size_t p, const glm::dmat3& rotation, ProbeSet& out) {
    const double weight = 4.0 * kPi / static_cast<double>(in_.directions.size());
    const sh::Rotation rot(o_.bands, rotation);
    rotated_.resize(n_);
    for (int c = 0; c < 3; ++c) {
      rotate(rot, &sums_.radiance[0][c], 3, weight, rotated_.data());
      for (int k = 0; k < n_; ++k)
        out.coefficients[p * n_ + k][c] = static_cast<float>(rotated_[k] + sums_.env_share * in_.env_sh.values[k][c] +
                                                             sums_.sun_visible * in_.sun_sh.values[k][c]);
    }
    const double fraction = static_cast<double>(sums_.backfaces) / static_cast<double>(in_.directions.size());
    out.backface_fraction[p] = static_cast<float>(fraction);
    out.valid[p] = fraction > o_.max_backface_fraction ? 0 : 1;
    if (ne_ == 0) return;
    float* m_out = out.transfer.data() + p * out.transfer_values_per_probe();
    for (int c = 0; c < in_.channels; ++c)
      for (int j = 0; j < ne_; ++j) {
        rotate(rot, sums_.transfer.data() + static_cast<std::size_t>(c) * n_ * ne_ + j, ne_, weight, rotated_.data());
        for (int k = 0; k < n_; ++k)
          m_out[(static_cast<std::size_t>(c) * n_ + k) * ne_ + j] = static_cast<float>(rotated_[k] + (k == j ? 1.0 : 0.0));
      }
    for (int c = 0; c < 3; ++c) {
      rotate(rot, &sums_.bias[0][c], 3, weight, rotated_.data());
      for (int k = 0; k < n_; ++k)
        out.transfer_bias[p * n_ + k][c] = static_cast<float>(rotated_[k] + sums_.sun_visible * in_.sun_sh.values[k][c]);
    }
  }

  const ProbeInputs& in_;
  const ProbeBakeOptions& o_;
  int n_, ne_;
  trace::RayBatch batch_, sun_batch_;
  std::vector<glm::vec3> batch_sum_;
  std::vector<double> env_basis_, column_, rotated_;
  ProbeSums sums_;
  std::uint64_t traced_ = 0;
};

// The empty output: positions, sky, parameters; coefficients zero, every probe valid.
ProbeSet empty_output(const ProbeSet& layout, const std::vector<glm::dvec3>& positions, const ProbeInputs& in,
                      const ProbeBakeOptions& o, const SceneLight& light, bool mesh_albedo) {
  const int n = o.bands * o.bands;
  ProbeSet out = layout;
  out.bands = o.bands;
  out.positions.assign(positions.begin(), positions.end());
  out.coefficients.assign(positions.size() * n, glm::vec3(0.0f));
  out.valid.assign(positions.size(), 1);
  out.backface_fraction.assign(positions.size(), 0.0f);
  out.sky = sh::RgbCoefficients(o.bands);
  for (int i = 0; i < n; ++i) out.sky.values[i] = in.env_sh.values[i] + in.sun_sh.values[i];
  out.parameters_json = parameters_json(o, light, mesh_albedo);
  return out;
}

// The transfer inputs (the baker's interreflected per-vertex transfer and the bias surface radiance of
// the sun and emission) and the transfer fields of `out`. Fills rep.transfer_rays, seconds_transfer.
void prepare_transfer(const trace::Scene& scene, const mesh::Mesh& mesh, const std::vector<glm::vec3>& albedo,
                      const SceneLight& light, const ProbeBakeOptions& o, SurfaceOptions bias_options, ProbeInputs& in,
                      ProbeSet& out, ProbeBakeReport& rep) {
  const auto start = std::chrono::steady_clock::now();
  const int tb = o.transfer_bands;
  bake::BakeOptions bo;
  bo.kind = transfer::Kind::interreflected;
  bo.bands = tb;
  bo.samples = o.surface_samples;
  bo.bounces = o.bounces;
  bo.albedo = o.albedo;
  bo.seed = o.seed;
  bo.threads = o.threads;
  bo.progress = o.progress;
  bo.dist = o.dist;  // interreflected: every rank gets the whole transfer
  bake::BakeReport bake_report;
  in.vertex_transfer = bake::bake(mesh, bo, &bake_report);
  in.channels = static_cast<int>(in.vertex_transfer.header.channels);
  bias_options.environment = false;
  std::uint64_t bias_rays = 0;
  if (light.sun || !light.emission.empty())
    in.bias_radiance = surface_radiance(scene, mesh, albedo, light, bias_options, &bias_rays);
  else
    in.bias_radiance.assign(mesh.positions.size(), glm::vec3(0.0f));
  rep.transfer_rays = bake_report.rays_traced + bias_rays;
  rep.seconds_transfer = seconds_since(start);
  const std::size_t count = out.positions.size();
  out.transfer_bands = tb;
  out.transfer_channels = in.channels;
  out.transfer.assign(count * out.transfer_values_per_probe(), 0.0f);
  out.transfer_bias.assign(count * static_cast<std::size_t>(o.bands * o.bands), glm::vec3(0.0f));
  out.transfer_environment = light.environment ? light::project(*light.environment, tb, o.threads) : sh::RgbCoefficients(tb);
  out.sky_bias = in.sun_sh;
}

// Rank 0 receives every rank's probes (the per-probe arrays bake() writes).
void gather_probes(const dist::Context& ranks, ProbeSet& out) {
  const std::size_t n = static_cast<std::size_t>(out.bands) * out.bands;
  dist::gather_items(ranks, out.coefficients, n);
  dist::gather_items(ranks, out.valid, 1);
  dist::gather_items(ranks, out.backface_fraction, 1);
  if (out.transfer_bands > 0) {
    dist::gather_items(ranks, out.transfer, out.transfer_values_per_probe());
    dist::gather_items(ranks, out.transfer_bias, n);
  }
}

// The ray set, its basis table and the pilot directions.
void prepare_rays(const ProbeBakeOptions& o, ProbeInputs& in) {
  const std::size_t samples = static_cast<std::size_t>(o.rays);
  const int n = o.bands * o.bands;
  for (const glm::dvec3& d : sh::sphere_directions(samples, o.seed)) in.directions.emplace_back(d);
  in.basis.resize(samples * n);
  for (std::size_t s = 0; s < samples; ++s) sh::eval(o.bands, in.directions[s], in.basis.data() + s * n);
  for (const glm::dvec3& d : sh::sphere_directions(kPilotRays, hash_to_u32(o.seed, 0, kPilotSalt)))
    in.pilot_directions.emplace_back(d);
}

}  // namespace

ProbeSet bake_probes(const mesh::Mesh& mesh, const SceneLight& light, const std::vector<glm::dvec3>& positions,
                     const ProbeSet& layout, const ProbeBakeOptions& o, ProbeBakeReport* report) {
  check_options(o);
  if (!light.emission.empty() && light.emission.size() != mesh.positions.size())
    fail("probes: emission must have one value per mesh vertex");
  if (positions.empty()) fail("probes: no probe positions");
  ProbeBakeReport local_report;
  ProbeBakeReport& rep = report ? *report : local_report;
  rep = ProbeBakeReport{};

  const std::vector<glm::vec3> albedo = bake::effective_albedo(mesh, o.albedo);
  auto start = std::chrono::steady_clock::now();
  const trace::Scene scene(mesh, trace::SceneOptions{o.threads});
  rep.seconds_build = seconds_since(start);

  // Surface radiance R_K (everything) and, for the transfer, its non-relightable part (sun, emission).
  start = std::chrono::steady_clock::now();
  const SurfaceOptions surface{o.surface_samples, o.sun_samples, o.bounces, true, o.seed, o.threads, o.progress, o.dist};
  const std::vector<glm::vec3> radiance = surface_radiance(scene, mesh, albedo, light, surface, &rep.surface_rays);
  rep.seconds_surface = seconds_since(start);

  ProbeInputs in;
  in.scene = &scene;
  in.mesh = &mesh;
  in.light = &light;
  in.options = &o;
  in.env_sh = light.environment ? light::project(*light.environment, o.bands, o.threads) : sh::RgbCoefficients(o.bands);
  in.sun_sh = light.sun ? sun_coefficients(o.bands, *light.sun) : sh::RgbCoefficients(o.bands);
  ProbeSet out = empty_output(layout, positions, in, o, light, !mesh.albedo.empty());
  if (o.transfer_bands > 0) prepare_transfer(scene, mesh, albedo, light, o, surface, in, out, rep);
  in.corner_radiance.resize(mesh.indices.size());
  for (std::size_t k = 0; k < mesh.indices.size(); ++k) in.corner_radiance[k] = radiance[mesh.indices[k]];
  const light::Environment lookup = light.environment ? lookup_environment(*light.environment) : light::Environment();
  in.environment = light.environment ? &lookup : nullptr;
  prepare_rays(o, in);

  start = std::chrono::steady_clock::now();
  const double cpu_start = process_cpu_seconds();
  Progress progress("probes", "probes", positions.size(), o.progress);
  std::atomic<std::uint64_t> rays_total{0};
  // Distributed: each rank bakes its share of the probes (in file order), rank 0 gathers them.
  const dist::Context& ranks = dist::or_single(o.dist);
  const dist::Range share = dist::my_range(ranks, positions.size());
  parallel_for(share.size(), 8, o.threads, [&](std::size_t chunk_begin, std::size_t chunk_end) {
    ProbeTracer tracer(in);
    for (std::size_t p = share.begin + chunk_begin; p < share.begin + chunk_end; ++p) tracer.bake(p, glm::vec3(positions[p]), out);
    rays_total += tracer.traced();
    progress.advance((chunk_end - chunk_begin) * static_cast<std::size_t>(ranks.size()));  // equal shares
  });
  progress.finish();
  gather_probes(ranks, out);
  rep.seconds_probes = seconds_since(start);
  rep.cpu_seconds_probes = process_cpu_seconds() - cpu_start;
  rep.probe_rays = ranks.sum(rays_total.load());
  rep.invalid = positions.size() - out.valid_count();
  return out;
}

void relight(ProbeSet& p, const sh::RgbCoefficients& environment) {
  if (p.transfer_bands == 0) fail("the probe file has no transfer (it was baked with transfer_bands 0)");
  const int n = static_cast<int>(p.coefficient_count()), ne = p.transfer_bands * p.transfer_bands;
  std::vector<glm::dvec3> lighting(ne, glm::dvec3(0.0));
  for (int j = 0; j < ne && j < static_cast<int>(environment.values.size()); ++j) lighting[j] = environment.values[j];
  for (std::size_t probe = 0; probe < p.count(); ++probe) {
    const float* m = p.transfer.data() + probe * p.transfer_values_per_probe();
    for (int k = 0; k < n; ++k) {
      glm::dvec3 sum = glm::dvec3(p.transfer_bias[probe * n + k]);
      for (int c = 0; c < 3; ++c) {
        const float* row = m + (static_cast<std::size_t>(p.transfer_channels == 1 ? 0 : c) * n + k) * ne;
        for (int j = 0; j < ne; ++j) sum[c] += row[j] * lighting[j][c];
      }
      p.coefficients[probe * n + k] = glm::vec3(sum);
    }
  }
  for (int k = 0; k < n; ++k)
    p.sky.values[k] = p.sky_bias.values[k] + (k < ne ? lighting[k] : glm::dvec3(0.0));
  sh::RgbCoefficients stored(p.transfer_bands);
  stored.values = lighting;
  p.transfer_environment = stored;
}

}  // namespace prt::probes
