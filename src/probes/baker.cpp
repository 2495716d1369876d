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
#include "core/error.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "light/environment.h"
#include "light/projection.h"
#include "probes/surface.h"
#include "sh/basis.h"
#include "sh/rotation.h"
#include "sh/sampling.h"
#include "trace/scene.h"

namespace prt::probes {

namespace {

constexpr double kPi = 3.14159265358979323846;

double process_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Uniform random rotation from three hashed numbers (Shoemake, "Uniform random rotations", GGems III).
glm::dmat3 probe_rotation(std::uint32_t seed, std::uint64_t probe) {
  const double u1 = hash_to_unit(seed, probe, 1), u2 = hash_to_unit(seed, probe, 2), u3 = hash_to_unit(seed, probe, 3);
  const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
  const glm::dquat q(b * std::cos(2.0 * kPi * u3), a * std::sin(2.0 * kPi * u2), a * std::cos(2.0 * kPi * u2),
                     b * std::sin(2.0 * kPi * u3));
  return glm::mat3_cast(glm::normalize(q));
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

// Per-vertex values interpolated at a hit: (1-u-v) a + u b + v c.
inline glm::vec3 interpolate(const std::vector<glm::vec3>& values, const std::uint32_t* tri, float u, float v) {
  return (1.0f - u - v) * values[tri[0]] + u * values[tri[1]] + v * values[tri[2]];
}

}  // namespace

void check_options(const ProbeBakeOptions& o) {
  if (o.bands < 1 || o.bands > 16) fail("--bands " + std::to_string(o.bands) + " is out of range 1..16");
  if (o.rays < 1 || o.rays > (1 << 20)) fail("--rays " + std::to_string(o.rays) + " is out of range 1..1048576");
  if (static_cast<double>(o.rays) * o.bands * o.bands > static_cast<double>(1 << 26))
    fail("--rays x --bands^2 is too large (more than 2^26 basis values)");
  if (o.bounces < 0 || o.bounces > 64) fail("--bounces " + std::to_string(o.bounces) + " is out of range 0..64");
  if (o.surface_samples < 1 || o.surface_samples > 65536)
    fail("--surface-samples " + std::to_string(o.surface_samples) + " is out of range 1..65536");
  if (o.sun_samples < 1 || o.sun_samples > 4096) fail("--sun-samples " + std::to_string(o.sun_samples) + " is out of range 1..4096");
  if (!(o.max_backface_fraction >= 0.0 && o.max_backface_fraction <= 1.0)) fail("--max-backface must lie in [0, 1]");
  if (o.transfer_bands < 0 || o.transfer_bands > 8) fail("--transfer-bands " + std::to_string(o.transfer_bands) + " is out of range 1..8");
  for (int c = 0; c < 3; ++c)
    if (!(o.albedo[c] >= 0.0f && o.albedo[c] <= 1.0f)) fail("--albedo components must lie in [0, 1]");
}

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
  SurfaceOptions surface{o.surface_samples, o.sun_samples, o.bounces, true, o.seed, o.threads, o.progress};
  const std::vector<glm::vec3> radiance = surface_radiance(scene, mesh, albedo, light, surface, &rep.surface_rays);
  rep.seconds_surface = seconds_since(start);

  const int bands = o.bands, n = bands * bands, tb = o.transfer_bands, ne = tb * tb;
  ProbeSet out = layout;
  out.bands = bands;
  out.positions.assign(positions.begin(), positions.end());
  const std::size_t count = positions.size();
  out.coefficients.assign(count * n, glm::vec3(0.0f));
  out.valid.assign(count, 1);
  out.backface_fraction.assign(count, 0.0f);
  const sh::RgbCoefficients env_sh = light.environment ? light::project(*light.environment, bands, o.threads) : sh::RgbCoefficients(bands);
  const sh::RgbCoefficients sun_sh = light.sun ? sun_coefficients(bands, *light.sun) : sh::RgbCoefficients(bands);
  out.sky = sh::RgbCoefficients(bands);
  for (int i = 0; i < n; ++i) out.sky.values[i] = env_sh.values[i] + sun_sh.values[i];
  out.parameters_json = parameters_json(o, light, !mesh.albedo.empty());

  // Transfer inputs: the baker's interreflected per-vertex transfer and the bias surface radiance.
  transfer::TransferData vertex_transfer;
  std::vector<glm::vec3> bias_radiance;
  int channels = 0;
  if (tb > 0) {
    start = std::chrono::steady_clock::now();
    bake::BakeOptions bo;
    bo.kind = transfer::Kind::interreflected;
    bo.bands = tb;
    bo.samples = o.surface_samples;
    bo.bounces = o.bounces;
    bo.albedo = o.albedo;
    bo.seed = o.seed;
    bo.threads = o.threads;
    bo.progress = o.progress;
    bake::BakeReport bake_report;
    vertex_transfer = bake::bake(mesh, bo, &bake_report);
    channels = static_cast<int>(vertex_transfer.header.channels);
    SurfaceOptions bias_options = surface;
    bias_options.environment = false;
    std::uint64_t bias_rays = 0;
    if (light.sun || !light.emission.empty())
      bias_radiance = surface_radiance(scene, mesh, albedo, light, bias_options, &bias_rays);
    else
      bias_radiance.assign(mesh.positions.size(), glm::vec3(0.0f));
    rep.transfer_rays = bake_report.rays_traced + bias_rays;
    rep.seconds_transfer = seconds_since(start);
    out.transfer_bands = tb;
    out.transfer_channels = channels;
    out.transfer.assign(count * out.transfer_values_per_probe(), 0.0f);
    out.transfer_bias.assign(count * n, glm::vec3(0.0f));
    out.transfer_environment = light.environment ? light::project(*light.environment, tb, o.threads) : sh::RgbCoefficients(tb);
    out.sky_bias = sun_sh;
  }

  // The surface radiance at each triangle's corners, triangle-major: one contiguous read per hit.
  std::vector<glm::vec3> corner_radiance(mesh.indices.size());
  for (std::size_t k = 0; k < mesh.indices.size(); ++k) corner_radiance[k] = radiance[mesh.indices[k]];
  const light::Environment lookup = light.environment ? lookup_environment(*light.environment) : light::Environment();
  const light::Environment* environment = light.environment ? &lookup : nullptr;

  // The ray set and its basis table (sample-major).
  const std::size_t samples = static_cast<std::size_t>(o.rays);
  std::vector<glm::vec3> directions;
  for (const glm::dvec3& d : sh::sphere_directions(samples, o.seed)) directions.emplace_back(d);
  std::vector<float> basis(samples * n);
  for (std::size_t s = 0; s < samples; ++s) sh::eval(bands, directions[s], basis.data() + s * n);
  const double weight = 4.0 * kPi / static_cast<double>(samples);
  const std::size_t transfer_stride = static_cast<std::size_t>(channels) * ne;  // per vertex in vertex_transfer

  start = std::chrono::steady_clock::now();
  const double cpu_start = process_cpu_seconds();
  Progress progress("probes", "probes", count, o.progress);
  std::atomic<std::uint64_t> rays_total{0};
  parallel_for(count, 8, o.threads, [&](std::size_t begin, std::size_t end) {
    trace::RayBatch batch(std::min<std::size_t>(samples, trace::kDefaultBatchCapacity));
    trace::RayBatch sun_batch(static_cast<std::size_t>(o.sun_samples));
    std::vector<glm::dvec3> local(n), local_bias(n);
    std::vector<glm::vec3> batch_sum(n);
    std::vector<double> column(n), rotated(n), env_basis(static_cast<std::size_t>(std::max(ne, 1)));
    std::vector<double> local_transfer(static_cast<std::size_t>(channels) * n * ne);
    std::uint64_t traced = 0;
    for (std::size_t p = begin; p < end; ++p) {
      const glm::dmat3 rotation = probe_rotation(o.seed, p);
      const glm::mat3 rotation_f(rotation);
      const glm::vec3 origin(positions[p]);
      std::fill(local.begin(), local.end(), glm::dvec3(0.0));
      std::fill(local_bias.begin(), local_bias.end(), glm::dvec3(0.0));
      std::fill(local_transfer.begin(), local_transfer.end(), 0.0);
      std::size_t backfaces = 0;
      double env_share = 0.0;
      for (std::size_t first = 0; first < samples; first += batch.capacity()) {
        const std::size_t batch_count = std::min(batch.capacity(), samples - first);
        batch.clear();
        for (std::size_t s = first; s < first + batch_count; ++s) batch.push(origin, rotation_f * directions[s]);
        scene.intersect(batch);
        traced += batch_count;
        // Per batch, the cheaper of two unbiased estimators of its share of c: with more misses than
        // hits, the control variate (its share of the exact c_env, corrected at the hits: environment
        // lookups only for hit rays, exact in open space); with more hits, plain Monte Carlo (lookups only
        // for escaping rays). Either way at most half the rays look up the environment.
        // The same loop prefetches each hit triangle's corner radiance: the random reads into that
        // triangle-major array were most of this pass's cost beyond Embree (cache misses, measured).
        std::size_t hits = 0;
        for (std::size_t i = 0; i < batch_count; ++i) {
          const trace::Hit& h = batch.data()[i].hit;
          if (h.geom_id == trace::kNoHit) continue;
          ++hits;
          const glm::vec3* corners = corner_radiance.data() + 3 * static_cast<std::size_t>(h.prim_id);
          __builtin_prefetch(corners);
          __builtin_prefetch(corners + 2);  // 36 bytes may straddle two cache lines
        }
        const bool plain = 2 * hits > batch_count;
        if (!plain) env_share += static_cast<double>(batch_count) / static_cast<double>(samples);
        std::fill(batch_sum.begin(), batch_sum.end(), glm::vec3(0.0f));
        for (std::size_t i = 0; i < batch_count; ++i) {
          const trace::HitResult hit = batch.hit(i);
          const trace::Ray& r = batch.data()[i].ray;
          const glm::vec3 dir(r.dir_x, r.dir_y, r.dir_z);
          const float* y = basis.data() + (first + i) * n;
          if (!hit.hit()) {
            if (plain && environment) {
              const glm::vec3 value(environment->radiance_float(dir));
              for (int k = 0; k < n; ++k) batch_sum[k] += value * y[k];
            }
            continue;
          }
          // Embree's geometric normal Ng points to the side from which the corners run counter-clockwise
          // (the same side as (p1 - p0) x (p2 - p0); checked against the MC reference's explicit cross
          // product in tests/probes): the ray meets a front face when it runs against Ng. Using Ng saves
          // loading the triangle's corners.
          const trace::Hit& h = batch.data()[i].hit;
          const bool front = h.ng_x * dir.x + h.ng_y * dir.y + h.ng_z * dir.z < 0.0f;
          glm::vec3 value(0.0f);
          if (!plain && environment) value = -environment->radiance_float(dir);
          if (front) {
            const glm::vec3* corner = corner_radiance.data() + 3 * static_cast<std::size_t>(hit.prim_id);
            value += (1.0f - hit.u - hit.v) * corner[0] + hit.u * corner[1] + hit.v * corner[2];
          } else {
            ++backfaces;
          }
          for (int k = 0; k < n; ++k) batch_sum[k] += value * y[k];
          if (tb > 0) {
            const std::uint32_t* tri = mesh.indices.data() + 3 * static_cast<std::size_t>(hit.prim_id);
            sh::eval(tb, glm::dvec3(dir), env_basis.data());
            glm::dvec3 bias(0.0);
            if (front) bias = glm::dvec3(interpolate(bias_radiance, tri, hit.u, hit.v));
            const float w0 = 1.0f - hit.u - hit.v;
            for (int c = 0; c < channels; ++c) {
              double* m = local_transfer.data() + static_cast<std::size_t>(c) * n * ne;
              for (int j = 0; j < ne; ++j) {
                double g = -env_basis[j];
                if (front) {
                  const std::size_t offset = static_cast<std::size_t>(c) * ne + j;
                  g += w0 * vertex_transfer.values[tri[0] * transfer_stride + offset] +
                       hit.u * vertex_transfer.values[tri[1] * transfer_stride + offset] +
                       hit.v * vertex_transfer.values[tri[2] * transfer_stride + offset];
                }
                for (int k = 0; k < n; ++k) m[static_cast<std::size_t>(k) * ne + j] += y[k] * g;
              }
            }
            for (int k = 0; k < n; ++k) local_bias[k] += bias * static_cast<double>(y[k]);
          }
        }
        for (int k = 0; k < n; ++k) local[k] += glm::dvec3(batch_sum[k]);
      }

      // Sun visibility from the probe.
      double sun_visible = 0.0;
      if (light.sun) {
        const auto scramble = static_cast<std::uint32_t>(hash_to_unit(o.seed, p, 0x5u) * 4294967296.0);
        sun_batch.clear();
        for (int k = 0; k < o.sun_samples; ++k) {
          const glm::dvec2 u = sh::sobol_2d(static_cast<std::uint32_t>(k), scramble);
          sun_batch.push(origin, glm::vec3(sun_direction_sample(*light.sun, u.x, u.y)));
        }
        scene.occluded(sun_batch);
        traced += sun_batch.size();
        sun_visible = 1.0 - static_cast<double>(sun_batch.occluded_count()) / o.sun_samples;
      }

      // Rotate the local sums to the world and add the exact parts.
      const sh::Rotation rot(bands, rotation);
      for (int c = 0; c < 3; ++c) {
        for (int k = 0; k < n; ++k) column[k] = local[k][c] * weight;
        rot.apply(column.data(), rotated.data());
        for (int k = 0; k < n; ++k)
          out.coefficients[p * n + k][c] = static_cast<float>(rotated[k] + env_share * env_sh.values[k][c] + sun_visible * sun_sh.values[k][c]);
      }
      const double fraction = static_cast<double>(backfaces) / static_cast<double>(samples);
      out.backface_fraction[p] = static_cast<float>(fraction);
      out.valid[p] = fraction > o.max_backface_fraction ? 0 : 1;
      if (tb > 0) {
        float* m_out = out.transfer.data() + p * out.transfer_values_per_probe();
        for (int c = 0; c < channels; ++c) {
          const double* m = local_transfer.data() + static_cast<std::size_t>(c) * n * ne;
          for (int j = 0; j < ne; ++j) {
            for (int k = 0; k < n; ++k) column[k] = m[static_cast<std::size_t>(k) * ne + j] * weight;
            rot.apply(column.data(), rotated.data());
            for (int k = 0; k < n; ++k)
              m_out[(static_cast<std::size_t>(c) * n + k) * ne + j] = static_cast<float>(rotated[k] + (k == j ? 1.0 : 0.0));
          }
        }
        for (int c = 0; c < 3; ++c) {
          for (int k = 0; k < n; ++k) column[k] = local_bias[k][c] * weight;
          rot.apply(column.data(), rotated.data());
          for (int k = 0; k < n; ++k)
            out.transfer_bias[p * n + k][c] = static_cast<float>(rotated[k] + sun_visible * sun_sh.values[k][c]);
        }
      }
    }
    rays_total += traced;
    progress.advance(end - begin);
  });
  progress.finish();
  rep.seconds_probes = seconds_since(start);
  rep.cpu_seconds_probes = process_cpu_seconds() - cpu_start;
  rep.probe_rays = rays_total.load();
  rep.invalid = count - out.valid_count();
  return out;
}

void relight(ProbeSet& p, const sh::RgbCoefficients& environment) {
  if (p.transfer_bands == 0) fail("the probe file has no transfer (bake it with --transfer)");
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
