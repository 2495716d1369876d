// Glossy bakes (bake.h, GLOSSY): the direct pass, interreflection passes and the file header.
#include <algorithm>
#include <chrono>
#include <memory>

#include <nlohmann/json.hpp>

#include "bake/glossy_passes.h"
#include "bake/mesh_brdfs.h"
#include "bake/passes.h"
#include "brdf/frame.h"
#include "brdf/projection.h"
#include "core/error.h"
#include "core/stopwatch.h"
#include "trace/scene.h"

namespace prt::bake {

namespace {

// Sum over vertices and channels of M[0][0]: the DC response of the transferred radiance to constant
// lighting (1 - occluded fraction of the sphere for the direct pass).
double pass_energy(const std::vector<float>& values, std::size_t matrix_size, std::size_t matrices) {
  double sum = 0.0;
  for (std::size_t i = 0; i < matrices; ++i) sum += values[i * matrix_size];
  return sum;
}

std::string parameters_json(const BakeOptions& o, const brdf::VertexBrdfs& brdfs, int bands_out, int bounces_done,
                            float ray_offset) {
  nlohmann::ordered_json j;
  j["tool"] = "prt 0.1.0";
  j["kind"] = transfer::kind_name(o.kind);
  j["bands"] = o.bands;
  j["bands_out"] = bands_out;
  brdf::write_vertex_brdfs(brdfs, j);
  j["samples"] = o.samples;
  j["seed"] = o.seed;
  j["sample_set"] = "owen-scrambled sobol, uniform hemisphere, per-vertex hashed rotation";
  j["frame"] = "local: t = normalize(+Y x n) (+X at the poles), b = n x t, z = n";
  j["ray_offset"] = ray_offset;
  if (o.footprint != mesh::Footprint::vertex) j["footprint"] = mesh::footprint_name(o.footprint);  // as bake.cpp
  if (o.kind == transfer::Kind::glossy_interreflected) {
    j["bounces_requested"] = o.bounces < 0 ? std::string("auto") : std::to_string(o.bounces);
    j["bounces"] = bounces_done;
  }
  return j.dump();
}

// The direct pass's one matrix per vertex repeated for three channels (vertex-major, channel blocks).
std::vector<float> three_channels(const std::vector<float>& direct, std::size_t vertices, std::size_t matrix_size) {
  std::vector<float> out(vertices * 3 * matrix_size);
  for (std::size_t v = 0; v < vertices; ++v)
    for (int c = 0; c < 3; ++c)
      std::copy(direct.begin() + v * matrix_size, direct.begin() + (v + 1) * matrix_size, out.begin() + (v * 3 + c) * matrix_size);
  return out;
}

// The BRDF of every vertex: options.brdf for all, or each material's (mesh_brdfs).
brdf::VertexBrdfs brdfs_of_vertices(const mesh::Mesh& mesh, const BakeOptions& options, std::vector<std::string>* notes) {
  if (!options.brdf_from_mesh) return brdf::VertexBrdfs{{options.brdf}, {}};
  if (mesh.materials.empty()) fail_option("brdf", " mesh: the mesh has no materials; give a BRDF spec");
  return mesh_brdfs(mesh, notes);
}

bool all_brdfs_grey(const brdf::VertexBrdfs& brdfs) {
  return std::all_of(brdfs.table.begin(), brdfs.table.end(), [](const brdf::Brdf& b) { return b.is_grey(); });
}

}  // namespace

transfer::TransferData bake_glossy(const mesh::Mesh& mesh, const BakeOptions& options, BakeReport* report) {
  BakeReport local_report;
  BakeReport& rep = report ? *report : local_report;
  rep = BakeReport{};
  const int bands_out = options.bands_out > 0 ? options.bands_out : options.bands;
  const bool interreflected = options.kind == transfer::Kind::glossy_interreflected;
  const brdf::VertexBrdfs brdfs = brdfs_of_vertices(mesh, options, &rep.notes);
  const int channels = interreflected && !all_brdfs_grey(brdfs) ? 3 : 1;
  const std::size_t vertices = mesh.positions.size();
  const std::size_t matrix_size = static_cast<std::size_t>(bands_out) * bands_out * options.bands * options.bands;

  transfer::TransferData data;
  transfer::Header& h = data.header;
  h.kind = options.kind;
  h.bands = static_cast<std::uint32_t>(options.bands);
  h.bands_out = static_cast<std::uint32_t>(bands_out);
  h.channels = static_cast<std::uint32_t>(channels);
  h.vertex_count = vertices;
  h.triangle_count = mesh.indices.size() / 3;
  h.mesh_fingerprint = mesh::fingerprint(mesh);

  auto start = std::chrono::steady_clock::now();
  auto scene = std::make_unique<trace::Scene>(mesh, bake_scene_options(options.threads));
  rep.seconds_build = seconds_since(start);
  const LocalSampleSet samples = make_uniform_sample_set(options.samples, options.bands, options.seed);
  const std::vector<std::uint32_t> order = trace::morton_order(mesh.positions);
  std::vector<glm::mat3> frames(vertices);
  for (std::size_t v = 0; v < vertices; ++v) frames[v] = brdf::shading_frame(mesh.normals[v]);
  const auto footprints = mesh::footprints_for(mesh, options.footprint);
  GlossyContext ctx{&mesh, scene.get(), &samples, &order, &frames, options.bands, bands_out,
                    options.seed, options.threads, options.progress, options.dist, footprints.get()};
  const dist::Context& dist = dist::or_single(options.dist);

  start = std::chrono::steady_clock::now();
  std::vector<float> direct;
  rep.rays_traced += glossy_direct_pass(ctx, direct);
  // Distributed: every rank needs the direct pass for the bounces, rank 0 alone for the file.
  if (interreflected) dist::allgather_items(dist, direct, matrix_size, &order);
  else dist::gather_items(dist, direct, matrix_size, &order);
  rep.seconds_visibility = seconds_since(start);
  data.values = channels == 1 ? std::move(direct) : three_channels(direct, vertices, matrix_size);
  rep.pass_energy.push_back(pass_energy(data.values, matrix_size, vertices * channels));

  if (interreflected) {
    use_robust_scene(scene, mesh, options.threads, rep.seconds_build);
    ctx.scene = scene.get();
    start = std::chrono::steady_clock::now();
    std::vector<brdf::BrdfMatrix> brdf_matrices;
    for (const brdf::Brdf& b : brdfs.table) brdf_matrices.push_back(brdf::project(b, bands_out));
    const int max_passes = options.bounces >= 0 ? options.bounces : kMaxAutoBounces;
    std::vector<float> prev = data.values, next;
    // The bounce-only part (interreflected minus direct) goes into the file's second section, so that a
    // renderer can shade a disc's direct light exactly and only its bounces through the transfer.
    data.bounce_only.assign(data.values.size(), 0.0f);
    h.bounce_only_section = true;
    for (int b = 1; b <= max_passes; ++b) {
      const std::string label = "bake glossy bounce " + std::to_string(b);
      rep.rays_traced += glossy_bounce_pass(ctx, brdf_matrices, brdfs, channels, prev, next, label.c_str());
      dist::allgather_items(dist, next, matrix_size * channels, &order);  // the next pass and the stopping rule need it
      for (std::size_t i = 0; i < next.size(); ++i) {
        data.values[i] += next[i];
        data.bounce_only[i] += next[i];
      }
      const double energy = pass_energy(next, matrix_size, vertices * channels);
      rep.pass_energy.push_back(energy);
      rep.bounces_done = b;
      prev.swap(next);
      if (options.bounces < 0 && !(std::abs(energy) >= kBounceEnergyThreshold * std::abs(rep.pass_energy.front()))) break;
    }
    rep.seconds_bounces = seconds_since(start);
  }
  rep.rays_traced = dist.sum(rep.rays_traced);
  h.parameters_json = parameters_json(options, brdfs, bands_out, rep.bounces_done, scene->ray_offset());
  return data;
}

}  // namespace prt::bake
