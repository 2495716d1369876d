#include "bake/bake.h"

#include <chrono>
#include <memory>

#include <nlohmann/json.hpp>

#include "bake/glossy_passes.h"
#include "bake/passes.h"
#include "bake/vertex_samples.h"
#include "core/big_buffer.h"
#include "core/error.h"
#include "core/stopwatch.h"
#include "sh/basis.h"
#include "trace/scene.h"

namespace prt::bake {

void validate_options(const BakeOptions& o) {
  if (o.bands < 1 || o.bands > sh::kMaxBands)
    fail_option("bands", " " + std::to_string(o.bands) + " is out of range 1.." + std::to_string(sh::kMaxBands));
  if (transfer::is_glossy(o.kind)) {
    if (o.brdf.empty() && !o.brdf_from_mesh) fail_option("brdf", std::string(": ") + transfer::kind_name(o.kind) + " transfer needs a BRDF spec");
    if (o.bands_out < 0 || o.bands_out > o.bands)
      fail_option("bands_out", " " + std::to_string(o.bands_out) + " is out of range 1..bands (" + std::to_string(o.bands) + ")");
  } else if (o.bands_out != 0) {
    fail_option("bands_out", " applies to glossy transfer only");
  }
  if (o.samples < 1 || o.samples > (1 << 20)) fail_option("samples", " " + std::to_string(o.samples) + " is out of range 1..1048576");
  if (o.bounces < -1 || o.bounces > 64) fail_option("bounces", " " + std::to_string(o.bounces) + " is out of range 0..64");
  for (int c = 0; c < 3; ++c)
    if (!(o.albedo[c] >= 0.0f && o.albedo[c] <= 1.0f)) fail_option("albedo", " components must lie in [0, 1]");
}

bool all_grey(const std::vector<glm::vec3>& albedo) {
  for (const glm::vec3& a : albedo)
    if (a.r != a.g || a.r != a.b) return false;
  return true;
}

int transfer_channels(const mesh::Mesh& mesh, const std::vector<glm::vec3>& albedo) {
  return all_grey(albedo) && !albedo_at_hits(mesh) ? 1 : 3;
}

double pass_energy(const std::vector<float>& values, std::size_t point_stride, std::size_t channel_stride, int channels) {
  double sum = 0.0;
  for (std::size_t base = 0; base < values.size(); base += point_stride)
    for (int c = 0; c < channels; ++c) sum += values[base + c * channel_stride];
  return sum;
}

std::vector<float> apply_albedo(std::vector<float>&& geometric, const std::vector<glm::vec3>& albedo, int channels, std::size_t n) {
  const std::size_t points = albedo.size();
  if (channels == 1) {
    std::vector<float> values = std::move(geometric);
    for (std::size_t v = 0; v < points; ++v)
      for (std::size_t i = 0; i < n; ++i) values[v * n + i] *= albedo[v].r;
    return values;
  }
  const std::size_t stride = 3 * n;
  std::vector<float> values;
  assign_big(values, points * stride, 0.0f);
  for (std::size_t v = 0; v < points; ++v)
    for (int c = 0; c < 3; ++c)
      for (std::size_t i = 0; i < n; ++i) values[v * stride + c * n + i] = albedo[v][c] * geometric[v * n + i];
  std::vector<float>().swap(geometric);
  return values;
}

namespace {

// out = channel transfer `free` (albedo-free, `channels` blocks of n floats per point) times each
// point's albedo per channel.
void fold_albedo(const std::vector<float>& free, const std::vector<glm::vec3>& albedo, int channels, std::size_t n,
                 std::vector<float>& out) {
  const std::size_t stride = n * static_cast<std::size_t>(channels);
  out.resize(free.size());
  for (std::size_t p = 0; p < albedo.size(); ++p)
    for (int ch = 0; ch < channels; ++ch)
      for (std::size_t c = 0; c < n; ++c) out[p * stride + ch * n + c] = albedo[p][ch] * free[p * stride + ch * n + c];
}

}  // namespace

std::vector<float> albedo_free_channels(const std::vector<float>& geometric, int channels, std::size_t n) {
  return apply_albedo(std::vector<float>(geometric), std::vector<glm::vec3>(geometric.size() / n, glm::vec3(1.0f)), channels, n);
}

void interreflect(const PassContext& ctx, const std::vector<glm::vec3>& albedo, int channels, const BakeOptions& options,
                  std::vector<float> prev, const PrevFromNext& prev_from_next, std::vector<float>& values,
                  std::vector<float>& bounce_only, BakeReport& rep) {
  const std::size_t n = static_cast<std::size_t>(options.bands) * options.bands;
  const std::size_t stride = n * static_cast<std::size_t>(channels);
  const int max_passes = options.bounces >= 0 ? options.bounces : kMaxAutoBounces;
  const bool at_hits = albedo_at_hits(*ctx.mesh);
  std::vector<float> next, shaded;
  bounce_only.assign(values.size(), 0.0f);
  const HitColours hit_colours(ctx);
  for (int b = 1; b <= max_passes; ++b) {
    const std::string label = "bake bounce " + std::to_string(b);
    rep.rays_traced += bounce_pass(ctx, hit_colours, albedo, channels, prev, next, label.c_str());
    // Distributed: the next pass and the stopping rule need every point's result.
    dist::allgather_items(dist::or_single(ctx.dist), next, stride, ctx.order);
    // At hits: next is albedo-free (the following pass gathers it); the receivers' albedo goes in here.
    if (at_hits) fold_albedo(next, albedo, channels, n, shaded);
    const std::vector<float>& pass = at_hits ? shaded : next;
    for (std::size_t i = 0; i < pass.size(); ++i) {
      values[i] += pass[i];
      bounce_only[i] += pass[i];
    }
    const double energy = pass_energy(pass, stride, n, channels);
    rep.pass_energy.push_back(energy);
    rep.bounces_done = b;
    if (options.bounces < 0 && !(energy >= kBounceEnergyThreshold * rep.pass_energy.front())) break;
    if (b < max_passes) prev_from_next(next, prev);
  }
}

std::string parameters_json(const BakeOptions& o, const mesh::Mesh& mesh, int bounces_done, float ray_offset) {
  nlohmann::ordered_json j;
  j["tool"] = "prt 0.1.0";
  j["kind"] = transfer::kind_name(o.kind);
  j["bands"] = o.bands;
  if (o.kind != transfer::Kind::unshadowed) {
    j["samples"] = o.samples;
    j["seed"] = o.seed;
    j["sample_set"] = "owen-scrambled sobol, cosine-weighted hemisphere, per-vertex hashed rotation";
    j["ray_offset"] = ray_offset;
    // Only for area, so that vertex bakes stay byte-identical to those of earlier versions.
    if (o.footprint != mesh::Footprint::vertex) j["footprint"] = mesh::footprint_name(o.footprint);
  }
  if (o.kind == transfer::Kind::interreflected) {
    j["bounces_requested"] = o.bounces < 0 ? std::string("auto") : std::to_string(o.bounces);
    j["bounces"] = bounces_done;
  }
  // "albedo_source" (docs/formats.md): absent for the default albedo, so such bakes keep their bytes.
  if (mesh.albedo.empty()) {
    j["albedo"] = {o.albedo.r, o.albedo.g, o.albedo.b};
    if (o.albedo_given) j["albedo_source"] = "option";
  } else {
    j["albedo"] = "mesh";
    j["albedo_source"] = mesh::albedo_source_name(mesh.albedo_source);
  }
  return j.dump();
}

std::vector<glm::vec3> effective_albedo(const mesh::Mesh& mesh, const glm::vec3& fallback) {
  if (!mesh.albedo.empty()) return mesh.albedo;
  return std::vector<glm::vec3>(mesh.positions.size(), fallback);
}

void use_robust_scene(std::unique_ptr<trace::Scene>& scene, const mesh::Mesh& mesh, int threads, double& build_seconds) {
  const auto start = std::chrono::steady_clock::now();
  scene.reset();
  scene = std::make_unique<trace::Scene>(mesh, trace::SceneOptions{threads, true});
  build_seconds += seconds_since(start);
}

trace::SceneOptions bake_scene_options(int threads) {
  trace::SceneOptions options;
  options.build_threads = threads;
  options.robust = false;
  return options;
}

transfer::TransferData bake(const mesh::Mesh& mesh, const BakeOptions& options, BakeReport* report) {
  validate_options(options);
  if (transfer::is_glossy(options.kind)) return bake_glossy(mesh, options, report);
  BakeReport local_report;
  BakeReport& rep = report ? *report : local_report;
  rep = BakeReport{};

  const std::vector<glm::vec3> albedo = effective_albedo(mesh, options.albedo);
  const int channels = transfer_channels(mesh, albedo);
  const std::size_t n = static_cast<std::size_t>(options.bands) * options.bands;
  const std::size_t vertices = mesh.positions.size();
  const std::size_t stride = n * static_cast<std::size_t>(channels);
  const dist::Context& dist = dist::or_single(options.dist);

  transfer::TransferData data;
  transfer::Header& h = data.header;
  h.kind = options.kind;
  h.bands = static_cast<std::uint32_t>(options.bands);
  h.channels = static_cast<std::uint32_t>(channels);
  h.vertex_count = vertices;
  h.triangle_count = mesh.indices.size() / 3;
  h.mesh_fingerprint = mesh::fingerprint(mesh);

  // Albedo-free transfer of the direct pass, then albedo applied per channel.
  std::vector<float> geometric;
  float ray_offset = 0.0f;
  if (options.kind == transfer::Kind::unshadowed) {
    auto start = std::chrono::steady_clock::now();
    unshadowed_geometric(mesh.normals, options.bands, options.threads, geometric);
    rep.seconds_visibility = seconds_since(start);
  }

  std::unique_ptr<trace::Scene> scene;
  LocalSampleSet samples;
  std::vector<std::uint32_t> order;
  PassContext ctx;
  std::unique_ptr<mesh::VertexFootprints> footprints;
  if (options.kind != transfer::Kind::unshadowed) {
    auto start = std::chrono::steady_clock::now();
    scene = std::make_unique<trace::Scene>(mesh, bake_scene_options(options.threads));
    rep.seconds_build = seconds_since(start);
    ray_offset = scene->ray_offset();
    samples = make_local_sample_set(options.samples, options.bands, options.seed);
    order = trace::morton_order(mesh.positions);
    ctx = PassContext{&mesh, scene.get(), &samples, &order, options.seed, options.threads, options.progress};
    ctx.dist = options.dist;
    footprints = mesh::footprints_for(mesh, options.footprint);
    ctx.footprints = footprints.get();
    start = std::chrono::steady_clock::now();
    rep.rays_traced += shadowed_geometric(ctx, geometric);
    // Distributed: every rank needs the direct pass for the bounces, rank 0 alone for the file.
    if (options.kind == transfer::Kind::interreflected) dist::allgather_items(dist, geometric, n, &order);
    else dist::gather_items(dist, geometric, n, &order);
    rep.seconds_visibility = seconds_since(start);
  }

  // What the first bounce pass gathers from, when it is not the direct pass's channel transfer.
  std::vector<float> source;
  if (options.kind == transfer::Kind::interreflected && albedo_at_hits(mesh)) source = albedo_free_channels(geometric, channels, n);
  data.values = apply_albedo(std::move(geometric), albedo, channels, n);
  rep.pass_energy.push_back(pass_energy(data.values, stride, n, channels));

  if (options.kind == transfer::Kind::interreflected) {
    use_robust_scene(scene, mesh, options.threads, rep.seconds_build);
    ctx.scene = scene.get();
    auto start = std::chrono::steady_clock::now();
    // The bounce-only part (interreflected minus direct) goes into the file's second section, so that a
    // renderer can shade a disc's direct light exactly and only its bounces through the transfer.
    h.bounce_only_section = true;
    interreflect(ctx, albedo, channels, options, source.empty() ? data.values : std::move(source), [](std::vector<float>& next, std::vector<float>& prev) { prev.swap(next); },
                 data.values, data.bounce_only, rep);
    rep.seconds_bounces = seconds_since(start);
  }

  rep.rays_traced = dist.sum(rep.rays_traced);
  h.parameters_json = parameters_json(options, mesh, rep.bounces_done, ray_offset);
  return data;
}

}  // namespace prt::bake
