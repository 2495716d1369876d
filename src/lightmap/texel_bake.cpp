#include "lightmap/texel_bake.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <memory>
#include <optional>

#include <nlohmann/json.hpp>

#include "bake/passes.h"
#include "bake/vertex_samples.h"
#include "core/big_buffer.h"
#include "core/error.h"
#include "core/memory_check.h"
#include "core/stopwatch.h"
#include "lightmap/gutter.h"
#include "lightmap/sample_repair.h"
#include "lightmap/uv_validation.h"
#include "trace/scene.h"
#include "trace/true_surface.h"
#include "transfer/mixed_parts.h"

namespace prt::lightmap {

namespace {

bool parse_side(const std::string& part, int& out) {
  if (part.empty() || part.size() > 6 || part.find_first_not_of("0123456789") != std::string::npos) return false;
  out = std::atoi(part.c_str());
  return true;
}

std::string size_text(const LightmapOptions& l) { return std::to_string(l.width) + "x" + std::to_string(l.height); }

}  // namespace

void parse_lightmap_size(const std::string& text, int& width, int& height) {
  const std::size_t x = text.find('x');
  const bool ok = x == std::string::npos ? parse_side(text, width) && parse_side(text, height = width)
                                         : parse_side(text.substr(0, x), width) && parse_side(text.substr(x + 1), height);
  if (!ok) fail_option("lightmap", ": expected WxH or SIZE (texels), got '" + text + "'");
  const int side_max = static_cast<int>(transfer::kMaxTexelSide);
  if (width < 1 || height < 1 || width > side_max || height > side_max)
    fail_option("lightmap", " " + text + ": each side must be 1.." + std::to_string(side_max) + " texels");
}

std::uint64_t estimated_bytes(const LightmapOptions& l, const bake::BakeOptions& o, int channels) {
  const std::uint64_t texels = std::uint64_t(l.width) * std::uint64_t(l.height);
  const std::uint64_t stride_bytes = 4ull * std::uint64_t(o.bands) * std::uint64_t(o.bands) * std::uint64_t(channels);
  // Per texel: raster state and coverage (~40 bytes), the sample (~80), and transfer buffers: values;
  // with bounces also bounce-only, prev grid, next and the per-sample sums (5 more).
  // --denoise: per section a second copy and the twicing residual, then the variances (2 floats) and the
  // stored weights (9 floats per level), and the interleaved sample sets (interleaved_tile_bits: 4^L x S
  // directions, each with its basis row and its padded copy: at most 12 + 8 bands^2 bytes); --stitch:
  // the seams' system, small.
  const std::uint64_t sections = o.kind == transfer::Kind::interreflected ? 2 : 1;
  const std::uint64_t buffers = (o.kind == transfer::Kind::interreflected ? 6 : 2) + (l.denoise ? 2 * sections : 0);
  const std::uint64_t denoise_bytes = l.denoise ? 8 + 36ull * std::uint64_t(std::max(0, l.denoise_options.iterations)) : 0;
  const std::uint64_t set_bytes = l.denoise ? (std::uint64_t(std::max(0, o.samples)) << (2 * interleaved_tile_bits(o.samples))) *
                                                  (12 + 8ull * std::uint64_t(o.bands) * std::uint64_t(o.bands))
                                            : 0;
  return texels * (120 + denoise_bytes + buffers * stride_bytes) + set_bytes;
}

void check_memory(const LightmapOptions& l, const bake::BakeOptions& o, int channels, std::uint64_t extra_bytes, std::uint64_t available) {
  check_memory_need("lightmap", size_text(l), estimated_bytes(l, o, channels) + extra_bytes, available);
}

TexelSamples texel_samples(const mesh::Mesh& mesh, const trace::Scene& scene, const std::vector<glm::vec3>& albedo,
                           const LightmapOptions& lightmap, std::uint32_t seed, int threads, LightmapReport* report) {
  LightmapReport local;
  if (!report) report = &local;
  if (!mesh.has_lightmap_uv()) fail_file(lightmap.mesh_path, "has no lightmap UVs (" + lightmap.missing_uv_reason + ")");
  std::vector<std::uint8_t> skip;
  UvProblems problems = check_texel_uvs(mesh, lightmap.vertex_triangles, skip);
  if (problems.tiling()) fail_file(lightmap.mesh_path, problems.message(mesh));
  auto start = std::chrono::steady_clock::now();
  TexelSamples samples = rasterize(mesh, albedo, lightmap.width, lightmap.height, threads, &skip);
  report->seconds_raster = seconds_since(start);
  add_raster_checks(problems, samples);
  if (problems.refused()) fail_file(lightmap.mesh_path, problems.message(mesh));
  report->uv_summary = problems.summary(mesh);
  report->covered = samples.samples.size();
  if (lightmap.repair) {
    start = std::chrono::steady_clock::now();
    const RepairReport repair = repair_samples(mesh, scene, samples, seed, threads);
    report->moved = repair.moved;
    report->unrecoverable = repair.unrecoverable;
    report->seconds_repair = seconds_since(start);
  }
  return samples;
}

BakedLightmap baked_lightmap(const transfer::Header& header, const std::string& path) {
  if (!header.is_texel()) fail_file(path, "not a lightmap (a per-vertex transfer file)");
  BakedLightmap out;
  out.options.width = static_cast<int>(header.texel_width);
  out.options.height = static_cast<int>(header.texel_height);
  const nlohmann::json j = nlohmann::json::parse(header.parameters_json, nullptr, false);
  if (!j.is_object() || !j.contains("lightmap") || !j["lightmap"].is_object())
    fail_file(path, "the bake parameters have no \"lightmap\" entry");
  const nlohmann::json& l = j["lightmap"];
  if (!l.value("gutter", nlohmann::json()).is_number_integer() || !l.value("sample_repair", nlohmann::json()).is_boolean())
    fail_file(path, "the bake parameters' \"lightmap\" entry lacks gutter or sample_repair");
  out.options.gutter = l["gutter"].get<int>();
  out.options.repair = l["sample_repair"].get<bool>();
  out.options.mesh_path = path;
  if (l.contains("seed") && l["seed"].is_number_unsigned()) out.seed = l["seed"].get<std::uint32_t>();
  // A mixed scene's texel file: its per-vertex triangles have no texels (transfer/mixed_parts.h).
  if (const std::optional<transfer::MixedParts> mixed = transfer::read_mixed_entry(header, path))
    out.options.vertex_triangles = transfer::vertex_triangle_mask(*mixed, header.triangle_count, path);
  return out;
}

void check_lightmap(const mesh::Mesh& mesh, const bake::BakeOptions& options, const LightmapOptions& lightmap) {
  bake::validate_options(options);
  if (transfer::is_glossy(options.kind))
    fail_option("lightmap", std::string(": ") + transfer::kind_name(options.kind) +
         " transfer per texel is not supported (glossy matrices per texel wait for transfer compression); use unshadowed, "
         "shadowed or interreflected");
  if (lightmap.gutter < 0 || lightmap.gutter > 64) fail_option("gutter", " " + std::to_string(lightmap.gutter) + " is out of range 0..64");
  const int side_max = static_cast<int>(transfer::kMaxTexelSide);
  if (lightmap.width < 1 || lightmap.height < 1 || lightmap.width > side_max || lightmap.height > side_max)
    fail_option("lightmap", " " + size_text(lightmap) + ": each side must be 1.." + std::to_string(side_max) + " texels");
  if (!mesh.has_lightmap_uv()) fail_file(lightmap.mesh_path, "has no lightmap UVs (" + lightmap.missing_uv_reason + ")");
  if (lightmap.denoise) validate_denoise_options(lightmap.denoise_options);
  check_memory(lightmap, options, bake::transfer_channels(mesh, bake::effective_albedo(mesh, options.albedo)),
               options.kind == transfer::Kind::interreflected ? bake::hit_colour_bytes(mesh) : 0);
}

namespace {

// A texel grid's layout: its coverage grown by the gutters, the gutter rounds, floats per texel.
struct GridShape {
  const std::vector<std::uint8_t>& coverage;  // grown by grow_gutter
  const std::vector<std::vector<std::uint32_t>>& rounds;
  std::size_t stride;
};

// Per-sample blocks into the texel grid (empty texels zero), then the gutters filled; in a mixed bake
// the vertex points' blocks follow the grid's (TexelGrid::vertex_base), in vertex order.
// A texel with extra points (InterleavedSampling::extra_sample, which follow the texel samples) gets the
// mean of its points, summed in point order.
struct GridWriter {
  const TexelSamples& samples;
  const std::vector<std::uint8_t>& coverage;  // grown by grow_gutter
  const std::vector<std::vector<std::uint32_t>>& rounds;
  std::size_t stride;
  std::size_t vertex_points = 0;  // after the texel samples (and extra points) in the per-point buffers
  const std::vector<std::uint32_t>* extra_sample = nullptr;

  void operator()(const std::vector<float>& per_point, std::vector<float>& grid) const {
    assign_big(grid, (coverage.size() + vertex_points) * stride, 0.0f);
    const std::size_t count = samples.samples.size(), extras = extra_sample ? extra_sample->size() : 0;
    for (std::size_t k = 0; k < count; ++k)
      std::copy_n(per_point.begin() + std::ptrdiff_t(k * stride), stride, grid.begin() + std::ptrdiff_t(samples.samples[k].texel * stride));
    if (extras) average_extras(per_point, grid);
    fill_gutter(grid, stride, coverage, rounds, samples.width, samples.height);
    std::copy_n(per_point.begin() + std::ptrdiff_t((count + extras) * stride), vertex_points * stride,
                grid.begin() + std::ptrdiff_t(coverage.size() * stride));
  }

 private:
  void average_extras(const std::vector<float>& per_point, std::vector<float>& grid) const {
    std::vector<std::uint8_t> points(samples.samples.size(), 1);
    for (std::size_t e = 0; e < extra_sample->size(); ++e) {
      const std::uint32_t k = (*extra_sample)[e];
      ++points[k];
      float* out = grid.data() + samples.samples[k].texel * stride;
      const float* in = per_point.data() + (samples.samples.size() + e) * stride;
      for (std::size_t c = 0; c < stride; ++c) out[c] += in[c];
    }
    for (std::size_t k = 0; k < points.size(); ++k) {
      if (points[k] == 1) continue;
      float* out = grid.data() + samples.samples[k].texel * stride;
      for (std::size_t c = 0; c < stride; ++c) out[c] /= float(points[k]);
    }
  }
};

// The bake's points: the texel samples, then the extra points of border texels (copies of the samples
// they add to, interleaved_sampling), then (mixed) every mesh vertex with a zero geometric normal
// (no true-surface rule: its rays leave from the vertex) and the vertex's albedo.
struct BakePoints {
  std::vector<glm::vec3> positions, normals, geometric_normals, albedo;
};

// Appends a point at texel sample `s` to `p`.
void add_sample_point(BakePoints& p, const mesh::Mesh& mesh, const TexelSample& s) {
  p.positions.push_back(s.position);
  p.normals.push_back(s.normal);
  p.geometric_normals.push_back(glm::vec3(trace::triangle_normal(mesh, s.triangle)));
  p.albedo.push_back(s.albedo);
}

BakePoints bake_points(const mesh::Mesh& mesh, const TexelSamples& samples, const std::vector<std::uint32_t>& extra_sample,
                       const std::vector<glm::vec3>& vertex_albedo, bool vertices) {
  BakePoints p;
  for (const TexelSample& s : samples.samples) add_sample_point(p, mesh, s);
  for (const std::uint32_t k : extra_sample) add_sample_point(p, mesh, samples.samples[k]);
  if (!vertices) return p;
  p.positions.insert(p.positions.end(), mesh.positions.begin(), mesh.positions.end());
  p.normals.insert(p.normals.end(), mesh.normals.begin(), mesh.normals.end());
  p.geometric_normals.resize(p.positions.size(), glm::vec3(0.0f));
  p.albedo.insert(p.albedo.end(), vertex_albedo.begin(), vertex_albedo.end());
  return p;
}

// The contact points of an interleaved bake (denoise.h, add_contact_sets), after its direct pass:
// `geometric` holds every point's albedo-free direct transfer so far (n floats each, point order, on
// every rank). The texels on a steep falloff of its first coefficient (each texel's mean over its points,
// through `dc_writer`: a GridWriter of stride 1) get extra points, traced here with `ctx`'s settings
// and appended to `sampling`, `points` and `geometric`. Returns the rays this rank traced.
std::uint64_t add_contact_points(const mesh::Mesh& mesh, const TexelSamples& samples, const GridWriter& dc_writer, const bake::PassContext& ctx,
                                 std::size_t n, InterleavedSampling& sampling, BakePoints& points, std::vector<float>& geometric) {
  std::vector<float> first_coefficient(geometric.size() / n), dc;
  for (std::size_t k = 0; k < first_coefficient.size(); ++k) first_coefficient[k] = geometric[k * n];
  dc_writer(first_coefficient, dc);
  const std::size_t first = sampling.extra_sample.size();
  if (add_contact_sets(samples, dc, sampling) == 0) return 0;
  BakePoints more;
  for (std::size_t e = first; e < sampling.extra_sample.size(); ++e) add_sample_point(more, mesh, samples.samples[sampling.extra_sample[e]]);
  const std::vector<std::uint8_t> sets(sampling.set.begin() + std::ptrdiff_t(samples.samples.size() + first), sampling.set.end());
  const std::vector<std::uint32_t> more_order = trace::morton_order(more.positions);
  bake::PassContext contact = ctx;
  contact.order = &more_order;
  contact.points = {&more.positions, &more.normals, &more.geometric_normals};
  contact.point_set = &sets;
  std::vector<float> more_geometric;
  const std::uint64_t rays = bake::shadowed_geometric(contact, more_geometric);
  dist::allgather_items(dist::or_single(ctx.dist), more_geometric, n, &more_order);
  geometric.insert(geometric.end(), more_geometric.begin(), more_geometric.end());
  for (auto [to, from] : {std::pair{&points.positions, &more.positions}, std::pair{&points.normals, &more.normals},
                          std::pair{&points.geometric_normals, &more.geometric_normals}, std::pair{&points.albedo, &more.albedo}})
    to->insert(to->end(), from->begin(), from->end());
  return rays;
}

// The shadowed direct pass over the points of `ctx` (albedo-free, n = bands^2 floats per point, into
// `geometric`), then an interleaved bake's contact points (`interleaved`, null for none; add_contact_points
// through a GridWriter of `shape`, stride 1), with `order` redone over every point when bounces follow.
// Distributed: every rank holds the result where the bounces or the contact points need it, else rank 0.
// Returns the rays this rank traced.
std::uint64_t shadowed_pass(const mesh::Mesh& mesh, const TexelSamples& samples, const GridShape& shape, transfer::Kind kind,
                            const bake::PassContext& ctx, InterleavedSampling* interleaved, BakePoints& points,
                            std::vector<std::uint32_t>& order, std::vector<float>& geometric) {
  const std::size_t n = std::size_t(ctx.samples->bands) * std::size_t(ctx.samples->bands);
  const dist::Context& dist = dist::or_single(ctx.dist);
  std::uint64_t rays = bake::shadowed_geometric(ctx, geometric);
  if (kind == transfer::Kind::interreflected || interleaved) dist::allgather_items(dist, geometric, n, &order);
  else dist::gather_items(dist, geometric, n, &order);
  if (!interleaved) return rays;
  const std::size_t traced = points.positions.size();
  rays += add_contact_points(mesh, samples, GridWriter{samples, shape.coverage, shape.rounds, shape.stride, 0, &interleaved->extra_sample},
                             ctx, n, *interleaved, points, geometric);
  if (points.positions.size() != traced && kind == transfer::Kind::interreflected) order = trace::morton_order(points.positions);
  return rays;
}

// Mixed: moves the vertex blocks after the texel grid (`texel_floats`) of `grid` into `vertices`.
void split_vertex_tail(std::vector<float>& grid, std::size_t texel_floats, std::vector<float>& vertices) {
  vertices.assign(grid.begin() + std::ptrdiff_t(texel_floats), grid.end());
  grid.resize(texel_floats);
}

// The per-vertex file's data of a mixed bake: the header of a vertex bake and the vertex blocks split
// off the texel grids.
transfer::TransferData vertex_transfer(const mesh::Mesh& mesh, const bake::BakeOptions& options, transfer::TransferData& texels,
                                       std::size_t texel_floats, int bounces_done, float ray_offset) {
  transfer::TransferData v;
  v.header.kind = options.kind;
  v.header.bands = texels.header.bands;
  v.header.channels = texels.header.channels;
  v.header.vertex_count = mesh.vertex_count();
  v.header.triangle_count = mesh.triangle_count();
  v.header.mesh_fingerprint = texels.header.mesh_fingerprint;
  v.header.bounce_only_section = texels.header.bounce_only_section;
  v.header.parameters_json = bake::parameters_json(options, mesh, bounces_done, ray_offset);
  split_vertex_tail(texels.values, texel_floats, v.values);
  if (!texels.bounce_only.empty()) split_vertex_tail(texels.bounce_only, texel_floats, v.bounce_only);
  return v;
}

std::string lightmap_parameters(const bake::BakeOptions& options, const mesh::Mesh& mesh, const LightmapOptions& l,
                                const LightmapReport& rep, float ray_offset) {
  nlohmann::ordered_json j = nlohmann::ordered_json::parse(bake::parameters_json(options, mesh, rep.bake.bounces_done, ray_offset));
  j["lightmap"] = {{"width", l.width},
                   {"height", l.height},
                   {"uv_set", mesh.lightmap_uv_set},
                   {"gutter", l.gutter},
                   {"sample_repair", l.repair},
                   {"seed", options.seed},
                   {"covered", rep.covered},
                   {"moved", rep.moved},
                   {"unrecoverable", rep.unrecoverable}};
  if (l.stitch)
    j["lightmap"]["stitch"] = {{"pull", l.stitch_options.pull}, {"gutter_weight", l.stitch_options.gutter_weight},
                               {"samples_per_texel", l.stitch_options.samples_per_texel}, {"seams", rep.stitch.seams}};
  if (l.denoise) {
    const DenoiseOptions& d = l.denoise_options;
    const bool interleave = l.interleaves();
    j["lightmap"]["denoise"] = {{"iterations", d.iterations}, {"plane_sigma", d.plane_sigma}, {"normal_power", d.normal_power},
                                {"value_sigma", d.value_sigma}, {"value_floor", d.value_floor}, {"floor_decay", d.floor_decay},
                                {"slope_ridge", d.slope_ridge}, {"twicing", d.twicing}, {"interleave", interleave}};
    if (interleave)
      j["sample_set"] = "owen-scrambled sobol, cosine-weighted hemisphere, interleaved blocks per texel, unturned frames, "
                        "border texels also trace their empty neighbours' blocks, contact texels three more";
  }
  return j.dump();
}

transfer::Header texel_header(const mesh::Mesh& mesh, const bake::BakeOptions& options, const LightmapOptions& l, int channels) {
  transfer::Header h;
  h.kind = options.kind;
  h.bands = static_cast<std::uint32_t>(options.bands);
  h.channels = static_cast<std::uint32_t>(channels);
  h.vertex_count = mesh.vertex_count();
  h.triangle_count = mesh.triangle_count();
  h.mesh_fingerprint = mesh::fingerprint(mesh);
  h.texel_width = static_cast<std::uint32_t>(l.width);
  h.texel_height = static_cast<std::uint32_t>(l.height);
  h.uv_set = mesh.lightmap_uv_set;
  h.uv_fingerprint = mesh::uv_fingerprint(mesh);
  h.bounce_only_section = options.kind == transfer::Kind::interreflected;
  return h;
}

// The optional passes over the finished grids (rank 0): denoising, then the gutters again, then seams.
void filter_texels(const mesh::Mesh& mesh, const TexelSamples& samples, const LightmapOptions& lightmap, int threads,
                   const GridShape& shape, transfer::TransferData& data, LightmapReport& rep) {
  if (lightmap.denoise) {
    const auto start = std::chrono::steady_clock::now();
    DenoiseOptions denoise = lightmap.denoise_options;
    denoise.threads = threads;
    denoise_texels(data.values, data.bounce_only, shape.stride, denoise_guides(mesh, samples), denoise);
    fill_gutter(data.values, shape.stride, shape.coverage, shape.rounds, lightmap.width, lightmap.height);
    if (!data.bounce_only.empty()) fill_gutter(data.bounce_only, shape.stride, shape.coverage, shape.rounds, lightmap.width, lightmap.height);
    rep.seconds_denoise = seconds_since(start);
  }
  if (lightmap.stitch) {
    const auto start = std::chrono::steady_clock::now();
    rep.stitch = stitch_seams(data.values, data.bounce_only, shape.stride, shape.coverage, lightmap.width, lightmap.height,
                              find_seams(mesh), lightmap.stitch_options);
    rep.seconds_stitch = seconds_since(start);
  }
}

}  // namespace

transfer::TransferData bake_lightmap(const mesh::Mesh& mesh, const bake::BakeOptions& options, const LightmapOptions& lightmap,
                                     LightmapReport* report, transfer::TransferData* vertex_data) {
  check_lightmap(mesh, options, lightmap);
  const bool mixed = lightmap.mixed();
  if (mixed && !vertex_data) fail("bake_lightmap: a mixed bake needs vertex_data");
  LightmapReport local;
  LightmapReport& rep = report ? *report : local;
  rep = LightmapReport{};
  const std::vector<glm::vec3> vertex_albedo = bake::effective_albedo(mesh, options.albedo);
  const int channels = bake::transfer_channels(mesh, vertex_albedo);
  auto start = std::chrono::steady_clock::now();
  const trace::Scene scene(mesh, trace::SceneOptions{options.threads, true});
  rep.bake.seconds_build = seconds_since(start);
  const TexelSamples samples = texel_samples(mesh, scene, vertex_albedo, lightmap, options.seed, options.threads, &rep);
  // Interleaved sample sets per texel sample, frames unturned (denoise.h).
  const bool interleave = lightmap.interleaves();
  InterleavedSampling interleaved = interleave ? interleaved_sampling(samples, options.samples, options.seed) : InterleavedSampling{};
  BakePoints points = bake_points(mesh, samples, interleaved.extra_sample, vertex_albedo, mixed);
  const std::vector<glm::vec3>& normals = points.normals;
  const std::vector<glm::vec3>& albedo = points.albedo;
  std::vector<std::uint8_t> coverage = samples.coverage;
  const auto rounds = grow_gutter(coverage, lightmap.width, lightmap.height, lightmap.gutter);
  rep.gutter = 0;
  for (const auto& round : rounds) rep.gutter += round.size();
  const std::size_t n = std::size_t(options.bands) * std::size_t(options.bands), stride = n * std::size_t(channels);
  const GridWriter to_grid{samples, coverage, rounds, stride, mixed ? mesh.vertex_count() : 0, &interleaved.extra_sample};

  std::vector<std::uint32_t> order = trace::morton_order(points.positions);
  const bake::LocalSampleSet set = interleave ? bake::make_interleaved_sample_sets(options.samples, options.bands, options.seed,
                                                                                   1 << (2 * interleaved.tile_bits))
                                              : bake::make_local_sample_set(options.samples, options.bands, options.seed);
  const bake::TexelGrid grid{&mesh.lightmap_uv, &coverage, lightmap.width, lightmap.height, mixed ? &lightmap.vertex_triangles : nullptr};
  bake::PassContext ctx{&mesh, &scene, &set, &order, options.seed, options.threads, options.progress,
                        {&points.positions, &points.normals, &points.geometric_normals}, &grid};
  ctx.dist = options.dist;
  if (interleave) {
    ctx.unturned_frames = true;
    ctx.point_set = &interleaved.set;
  }
  // Mixed: the vertices' rays leave from their footprints (--footprint), as in a vertex bake.
  const std::unique_ptr<mesh::VertexFootprints> footprints = mixed ? mesh::footprints_for(mesh, options.footprint) : nullptr;
  ctx.footprints = footprints.get();
  ctx.footprint_first = samples.samples.size() + interleaved.extra_sample.size();
  const dist::Context& dist = dist::or_single(options.dist);
  start = std::chrono::steady_clock::now();
  std::vector<float> geometric;
  if (options.kind == transfer::Kind::unshadowed)
    bake::unshadowed_geometric(normals, options.bands, options.threads, geometric);
  else
    rep.bake.rays_traced += shadowed_pass(mesh, samples, {coverage, rounds, 1}, options.kind, ctx, interleave ? &interleaved : nullptr,
                                          points, order, geometric);
  rep.bake.seconds_visibility = seconds_since(start);
  // What the first bounce pass gathers from: the direct pass, or its albedo-free transfer (albedo_at_hits).
  std::vector<float> source;
  if (options.kind == transfer::Kind::interreflected && bake::albedo_at_hits(mesh))
    source = bake::albedo_free_channels(geometric, channels, n);
  std::vector<float> values = bake::apply_albedo(std::move(geometric), albedo, channels, n), bounce_only;
  rep.bake.pass_energy.push_back(bake::pass_energy(values, stride, n, channels));

  transfer::TransferData data;
  data.header = texel_header(mesh, options, lightmap, channels);
  if (options.kind == transfer::Kind::interreflected) {
    start = std::chrono::steady_clock::now();
    std::vector<float> prev;
    to_grid(source.empty() ? values : source, prev);
    bake::interreflect(ctx, albedo, channels, options, std::move(prev),
                       [&](std::vector<float>& next, std::vector<float>& prev_grid) { to_grid(next, prev_grid); }, values,
                       bounce_only, rep.bake);
    rep.bake.seconds_bounces = seconds_since(start);
    to_grid(bounce_only, data.bounce_only);
  }
  to_grid(values, data.values);
  if (mixed) *vertex_data = vertex_transfer(mesh, options, data, coverage.size() * stride, rep.bake.bounces_done, scene.ray_offset());
  if (dist.is_root()) filter_texels(mesh, samples, lightmap, options.threads, {coverage, rounds, stride}, data, rep);  // rank 0 holds it all
  data.coverage = std::move(coverage);
  rep.bake.rays_traced = dist.sum(rep.bake.rays_traced);
  data.header.parameters_json = lightmap_parameters(options, mesh, lightmap, rep, scene.ray_offset());
  return data;
}

}  // namespace prt::lightmap
