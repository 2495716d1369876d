// prt bake: bakes per-vertex transfer (src/bake: diffuse vectors, glossy matrices) and writes the .prt file (and a .glb).
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>

#include "bake/bake.h"
#include "brdf/brdf.h"
#include "cli/arguments.h"
#include "cli/output_paths.h"
#include "cli/commands.h"
#include "cli/distributed.h"
#include "compress/compressed.h"
#include "compress/ship_defaults.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/memory_check.h"
#include "core/stopwatch.h"
#include "core/text.h"
#include "lightmap/part_choice.h"
#include "lightmap/texel_bake.h"
#include "lightmap/uv_source.h"
#include "mesh/mesh.h"
#include "pipeline/mixed_outputs.h"
#include "pipeline/mixed_uv_mesh.h"
#include "pipeline/transfer_outputs.h"
#include "transfer/transfer_file.h"

namespace prt::cli {

namespace {

struct BakeCommandOptions {
  std::string mesh_path;
  int scene = mesh::kDefaultScene;
  std::string output;
  std::string gltf_output;
  std::string kind = "shadowed";
  std::string albedo;
  std::string brdf;
  std::string compress;  // "K,N": write a .cprt instead of the .prt; empty with -o *.cprt: the ship default
  std::string footprint = "area";  // docs/conventions.md "Vertex footprint": contact stays lit
  int bands = 0;  // 0: the default of the output's form (compress/ship_defaults.h)
  int bands_out = 0;
  int samples = 1024;
  int bounces = -1;
  unsigned seed = 1;
  int threads = 0;
  bool quiet = false;
  bool float16 = false;
  std::string lightmap;  // "WxH" or "SIZE": bake texels (src/lightmap)
  int gutter = 2;
  bool no_repair = false;
  bool denoise = false;  // --lightmap: filter the texel transfer (lightmap/denoise.h)
  bool stitch = false;   // --lightmap: stitch the seams (lightmap/seams.h)
  std::string uv = "file";  // --lightmap: file | auto | generate (lightmap/uv_source.h)
  std::string texel_parts = "all";  // --lightmap: all | auto | NAME,NAME (lightmap/part_choice.h)
};

// Everything of the command line that changes the output (dist: every rank must bake the same job).
std::string canonical_options(const BakeCommandOptions& o, const bake::BakeOptions& b) {
  return std::string("bake ") + transfer::kind_name(b.kind) + " bands " + std::to_string(b.bands) + " out " +
         std::to_string(b.bands_out) + " samples " + std::to_string(b.samples) + " bounces " + std::to_string(b.bounces) +
         " albedo " + exact(b.albedo.r) + "," + exact(b.albedo.g) + "," + exact(b.albedo.b) + " seed " +
         std::to_string(b.seed) + " footprint " + mesh::footprint_name(b.footprint) + " brdf " + (b.brdf_from_mesh ? "mesh" : b.brdf.empty() ? "" : brdf::to_spec(b.brdf)) + " float16 " +
         std::to_string(o.float16) + " compress " + o.compress + " gltf " + std::to_string(!o.gltf_output.empty()) +
         " lightmap " + o.lightmap + " gutter " + std::to_string(o.gutter) + " repair " + std::to_string(!o.no_repair) + " uv " + o.uv +
         (o.texel_parts == "all" ? "" : " texel-parts " + o.texel_parts) + " denoise " + std::to_string(o.denoise) + " stitch " + std::to_string(o.stitch);
}

// Bytes a per-vertex bake of `vertices` needs at most: the sample set's basis (samples x bands^2
// floats), per vertex the transfer (three channels; glossy: bands_out^2 x bands^2 per channel) in up
// to four buffers with bounces (values, bounce-only, previous and next pass), and the file's copy.
std::uint64_t estimated_bake_bytes(const bake::BakeOptions& b, const mesh::Mesh& mesh) {
  const std::uint64_t n = std::uint64_t(b.bands) * std::uint64_t(b.bands);
  const std::uint64_t out = transfer::is_glossy(b.kind) ? std::uint64_t(b.bands_out ? b.bands_out : b.bands) : 1;
  const std::uint64_t per_vertex = 4 * 3 * n * out * out;
  const bool bounces = b.kind == transfer::Kind::interreflected || b.kind == transfer::Kind::glossy_interreflected;
  return std::uint64_t(b.samples) * n * 4 + saturating_product(mesh.positions.size(), per_vertex * (bounces ? 5 : 2)) +
         (bounces ? bake::hit_colour_bytes(mesh) : 0);
}

// The bake's summary line: what was baked, rays, bounces, time, output.
void print_summary(const std::string& what, const bake::BakeReport& report, transfer::Kind kind, double seconds,
                   const std::string& output) {
  std::fprintf(stderr, "prt bake: %s", what.c_str());
  if (report.rays_traced > 0)
    std::fprintf(stderr, ", %llu rays (%.2f Mrays/s)", static_cast<unsigned long long>(report.rays_traced),
                 report.rays_traced / 1e6 / std::max(1e-9, report.seconds_visibility + report.seconds_bounces));
  if (kind == transfer::Kind::interreflected || kind == transfer::Kind::glossy_interreflected)
    std::fprintf(stderr, ", %d bounce(s)", report.bounces_done);
  std::fprintf(stderr, "%s, %.2f s -> %s\n", job_summary().c_str(), seconds, output.c_str());
}

// The compressed default ("bake high, ship light", docs/conventions.md): a diffuse bake, per vertex or
// per texel, written to a .cprt without --compress: kHighBands bands (unless --bands), CPCA with
// compress::ship_compression (per texel: ship_texel_compression), float16 (K and N sized to the 5-band
// file). Every other bake keeps its form: kShipBands bands by default, uncompressed unless --compress.
bool ships_compressed(const BakeCommandOptions& o, const bake::BakeOptions& options) {
  return o.compress.empty() && !transfer::is_glossy(options.kind) && lower_extension(o.output) == ".cprt";
}

// The ship default's CPCA setting for baked `data` into `out` (K, N; fitted to `prior`, which must
// outlive `out`).
void set_ship_compression(const transfer::TransferData& data, const sh::RgbCoefficients& prior, pipeline::TransferOutputs& out) {
  const transfer::Header& h = data.header;
  const int channels = static_cast<int>(h.channels), sections = data.bounce_only.empty() ? 1 : 2, bands = static_cast<int>(h.bands);
  compress::ShipCompression ship;
  if (h.is_texel()) {
    const std::uint64_t points = compress::point_blocks(h, data.coverage).size();
    ship = compress::ship_texel_compression(points, static_cast<std::uint64_t>(h.texel_width) * h.texel_height, channels, sections, bands);
  } else {
    ship = compress::ship_compression(h.vertex_count, channels, sections, bands);
  }
  out.clusters = ship.clusters;
  out.pca = ship.pca;
  out.fit_points = ship.fit_points;
  out.rounds = ship.rounds;
  out.metric_sky = &prior;
}

// Per vertex: checks, bakes (split over the ranks of an MPI job) and writes the outputs from rank 0.
void bake_vertices(const BakeCommandOptions& o, const bake::BakeOptions& options, pipeline::TransferOutputs out) {
  if (transfer::is_glossy(options.kind) && !o.gltf_output.empty())
    fail("--gltf: glTF export of glossy transfer matrices is not supported; use the .prt file");
  // Check the outputs before spending minutes baking (rank 0 alone writes them).
  if (job().is_root()) check_outputs({o.output, o.gltf_output}, {o.mesh_path, o.brdf});
  mesh::LoadReport load_report;
  // --brdf mesh: the materials are checked before the loader's notes are printed (bad input is one line).
  const bool notes = !o.quiet && job().is_root();
  const mesh::Mesh mesh =
      load_mesh_for_albedo(o.mesh_path, o.albedo, {o.scene, !notes || options.brdf_from_mesh}, &load_report);
  if (options.brdf_from_mesh) {
    if (mesh.materials.empty())
      fail_file(o.mesh_path, !o.albedo.empty() ? "--albedo replaces the materials (if any) that --brdf mesh needs; give --brdf SPEC"
                             : o.brdf.empty()  ? "has no materials, so glossy transfer needs --brdf SPEC"
                                               : "has no materials for --brdf mesh; give --brdf SPEC");
    if (notes)
      for (const std::string& note : load_report.notes) std::cerr << o.mesh_path << ": " << note << "\n";
  }
  const int bands_out = options.bands_out ? options.bands_out : options.bands;
  const std::string sized_by = std::to_string(options.bands) +
                               (transfer::is_glossy(options.kind) ? " --bands-out " + std::to_string(bands_out) : "") +
                               " --samples " + std::to_string(o.samples) + " for " +
                               std::to_string(mesh.positions.size()) + " vertices";
  check_memory_need("bands", sized_by, estimated_bake_bytes(options, mesh));
  check_job_inputs({mesh_input(o.mesh_path, mesh), options_input(canonical_options(o, options))});
  const auto start = std::chrono::steady_clock::now();
  bake::BakeReport report;
  transfer::TransferData data = bake::bake(mesh, options, &report);
  if (!job().is_root()) return;  // only rank 0 holds the whole result
  for (const std::string& note : report.notes) std::cerr << o.mesh_path << ": " << note << "\n";
  const double seconds = seconds_since(start);
  const transfer::Header header = data.header;
  const sh::RgbCoefficients prior = compress::ship_metric_sky(static_cast<int>(header.bands));
  if (ships_compressed(o, options)) set_ship_compression(data, prior, out);  // K and N sized to the mesh
  pipeline::write_transfer_outputs(mesh, std::move(data), out);
  if (o.quiet) return;
  std::string what = std::string(transfer::kind_name(options.kind)) + ", " + std::to_string(mesh.positions.size()) +
                     " vertices, " + std::to_string(header.bands) + " bands, " + std::to_string(header.channels) +
                     " channel(s)";
  if (transfer::is_glossy(options.kind))
    what += ", " + std::to_string(header.bands_out * header.bands_out) + " x " +
            std::to_string(header.bands * header.bands) + " matrices";
  print_summary(what, report, options.kind, seconds, o.output);
}

// What a mixed bake writes: the pair, the --gltf (if any) and, with generated UVs, the mesh that carries them.
std::vector<std::string> mixed_output_paths(const BakeCommandOptions& o, bool uv_generated) {
  std::vector<std::string> paths = {o.output, o.gltf_output, pipeline::mixed_vertex_path(o.output)};
  if (uv_generated) paths.push_back(pipeline::mixed_mesh_path(o.output));
  return paths;
}

// --texel-parts: which parts are baked per texel (lightmap/part_choice.h); for a mixed scene sets
// lightmap.vertex_triangles and checks what a mixed bake writes (a .prt pair and the --gltf, no --compress;
// with generated UVs also the mesh that carries them, pipeline/mixed_uv_mesh.h).
lightmap::PartChoice choose_mixed_parts(const BakeCommandOptions& o, const mesh::Mesh& mesh, lightmap::LightmapOptions& lightmap,
                                        bool uv_generated) {
  lightmap::PartChoice parts = lightmap::choose_parts(mesh, o.texel_parts, lightmap.width, lightmap.height, o.mesh_path);
  if (!parts.mixed()) return parts;
  if (!o.compress.empty() || lower_extension(o.output) != ".prt")
    fail("-o " + o.output + ": a mixed scene (--texel-parts) is written as a .prt pair (no --compress, no .cprt)");
  if (job().is_root()) check_outputs(mixed_output_paths(o, uv_generated), {o.mesh_path});
  lightmap.vertex_triangles = parts.vertex_triangle;
  return parts;
}

// The lightmap UVs (lightmap/uv_source.h) and the parts. With --uv auto and parts named or auto, the
// parts are chosen on the file's UVs first, so that auto judges the texel parts' UVs alone (a
// per-vertex part's UVs are never read). A mixed scene with generated UVs is then baked on the mesh
// as loaded back from the file that carries them (`uv_mesh`, committed with the pair).
lightmap::PartChoice choose_uvs_and_parts(const BakeCommandOptions& o, mesh::Mesh& mesh, lightmap::LightmapOptions& lightmap, int threads,
                                          lightmap::UvSourceReport& uv_source, std::optional<pipeline::MixedUvMesh>& uv_mesh) {
  const lightmap::UvMode uv_mode = lightmap::parse_uv_mode(o.uv);
  const bool parts_first = uv_mode == lightmap::UvMode::automatic && mesh.has_lightmap_uv() && o.texel_parts != "all";
  lightmap::PartChoice parts = parts_first ? choose_mixed_parts(o, mesh, lightmap, false) : lightmap::PartChoice{};
  lightmap::choose_lightmap_uvs(mesh, uv_mode, lightmap, threads, &uv_source);
  if (!parts_first) parts = choose_mixed_parts(o, mesh, lightmap, uv_source.generated);
  if (!parts.mixed() || !uv_source.generated) return parts;
  if (parts_first && job().is_root()) check_outputs(mixed_output_paths(o, true), {o.mesh_path});
  uv_mesh.emplace(pipeline::mixed_mesh_path(o.output), o.mesh_path, mesh, parts.vertex_triangle);
  mesh = std::move(uv_mesh->loaded());
  lightmap.vertex_triangles = uv_mesh->vertex_triangle();
  return parts;
}

// A mixed scene's outputs: the mesh with generated UVs (if any), the .prt pair and the engine glTF
// (of the mesh with the generated UVs, if any: the mesh the pair was baked for), the mesh removed again
// if the others cannot be written.
void write_mixed(const BakeCommandOptions& o, const mesh::Mesh& mesh, transfer::TransferData texels, transfer::TransferData vertices,
                 const lightmap::LightmapOptions& lightmap, const lightmap::PartChoice& parts, std::optional<pipeline::MixedUvMesh>& uv_mesh,
                 const pipeline::TransferOutputs& out) {
  if (uv_mesh) uv_mesh->commit();
  pipeline::MixedOutputs outputs;
  outputs.texel_path = o.output;
  outputs.vertex_path = pipeline::mixed_vertex_path(o.output);
  outputs.gltf_path = o.gltf_output;
  outputs.gltf_source = uv_mesh ? uv_mesh->path() : o.mesh_path;
  outputs.vertex_triangle = lightmap.vertex_triangles;
  outputs.texel_parts = parts.texel_parts;
  outputs.vertex_parts = parts.vertex_parts;
  outputs.float16 = out.float16;
  outputs.seed = out.seed;
  outputs.threads = out.threads;
  try {
    pipeline::write_mixed_outputs(mesh, std::move(texels), std::move(vertices), outputs);
  } catch (...) {
    std::error_code ignored;
    if (uv_mesh) std::filesystem::remove(uv_mesh->path(), ignored);
    throw;
  }
}

// Per texel of the mesh's lightmap UVs (src/lightmap): checks everything (options, outputs, UVs,
// memory), bakes (split over the ranks) and writes the outputs from rank 0.
void bake_texels(const BakeCommandOptions& o, const bake::BakeOptions& options, const pipeline::TransferOutputs& out) {
  lightmap::LightmapOptions lightmap;
  lightmap::parse_lightmap_size(o.lightmap, lightmap.width, lightmap.height);
  lightmap.gutter = o.gutter;
  lightmap.repair = !o.no_repair;
  lightmap.denoise = o.denoise;
  lightmap.stitch = o.stitch;
  lightmap.mesh_path = o.mesh_path;
  if (job().is_root()) check_outputs({o.output, o.gltf_output}, {o.mesh_path});
  lightmap::parse_uv_mode(o.uv);  // a bad --uv before the mesh is loaded
  mesh::LoadReport load_report;
  mesh::Mesh mesh = load_mesh_for_albedo(o.mesh_path, o.albedo, {o.scene, o.quiet || !job().is_root()}, &load_report);
  lightmap.missing_uv_reason = load_report.missing_uv_reason;
  lightmap::UvSourceReport uv_source;
  std::optional<pipeline::MixedUvMesh> uv_mesh;
  const lightmap::PartChoice parts = choose_uvs_and_parts(o, mesh, lightmap, options.threads, uv_source, uv_mesh);
  if (uv_source.generated && !o.quiet && job().is_root())
    std::fprintf(stderr, "%s: lightmap UVs generated (%s): %zu charts, %.1f%% of the lightmap filled, %.2f s; %s\n", o.mesh_path.c_str(),
                 uv_source.reason.c_str(), uv_source.unwrap.charts, 100.0 * uv_source.unwrap.fill, uv_source.unwrap.seconds,
                 uv_mesh ? ("shade and render the pair with " + uv_mesh->path() + ", which carries them").c_str()
                         : "render the --gltf output, which carries its own model of the transfer (for a .prt that renders with a "
                           "mesh file, bake prt unwrap's file)");
  lightmap::check_lightmap(mesh, options, lightmap);
  check_job_inputs({mesh_input(o.mesh_path, mesh), options_input(canonical_options(o, options))});
  const auto start = std::chrono::steady_clock::now();
  lightmap::LightmapReport report;
  transfer::TransferData vertex_data;
  transfer::TransferData data = lightmap::bake_lightmap(mesh, options, lightmap, &report, &vertex_data);
  if (!job().is_root()) return;  // only rank 0 holds the whole result
  if (!o.quiet)
    for (const std::string& line : report.uv_summary) std::fprintf(stderr, "%s: %s\n", o.mesh_path.c_str(), line.c_str());
  const transfer::Header header = data.header;
  pipeline::TransferOutputs outputs = out;
  outputs.uv_generated = uv_source.generated;  // the glTF then carries the generated UVs
  if (parts.mixed()) {
    write_mixed(o, mesh, std::move(data), std::move(vertex_data), lightmap, parts, uv_mesh, out);
  } else {
    const sh::RgbCoefficients prior = compress::ship_metric_sky(static_cast<int>(header.bands));
    if (ships_compressed(o, options)) set_ship_compression(data, prior, outputs);  // K and N sized to the texels
    pipeline::write_transfer_outputs(mesh, std::move(data), outputs);
  }
  if (o.quiet) return;
  char what[256];
  std::snprintf(what, sizeof what,
                "%s lightmap %dx%d, %zu covered texels, %zu gutter, %zu samples moved out of geometry, %zu unrecoverable, "
                "%u bands, %u channel(s)",
                transfer::kind_name(options.kind), lightmap.width, lightmap.height, report.covered, report.gutter,
                report.moved, report.unrecoverable, header.bands, header.channels);
  std::string summary = what;
  if (parts.mixed())
    summary += ", " + std::to_string(parts.texel_parts.size()) + " part(s) per texel, " + std::to_string(parts.vertex_parts.size()) +
               " per vertex (" + std::to_string(mesh.vertex_count()) + " vertices -> " + pipeline::mixed_vertex_path(o.output) + ")";
  char extra[128];
  if (lightmap.denoise) {
    std::snprintf(extra, sizeof extra, ", denoised in %.2f s", report.seconds_denoise);
    summary += extra;
  }
  if (lightmap.stitch) {
    std::snprintf(extra, sizeof extra, ", %zu seam edges stitched in %.2f s", report.stitch.seams, report.seconds_stitch);
    summary += extra;
  }
  print_summary(summary, report.bake, options.kind, seconds_since(start), o.output);
}

void run_bake(const BakeCommandOptions& o) {
  bake::BakeOptions options;
  options.kind = transfer::parse_kind(o.kind);
  options.footprint = mesh::parse_footprint(o.footprint, "--footprint");
  options.bands = o.bands;  // resolved below, once the kind is known
  options.samples = o.samples;
  options.bounces = o.bounces;
  options.seed = o.seed;
  options.threads = o.threads;
  options.progress = want_progress(o.quiet) && job().is_root();
  options.dist = &job();
  if (!o.albedo.empty()) options.albedo = glm::vec3(parse_triple(o.albedo, "--albedo", "R,G,B in [0,1]"));
  options.albedo_given = !o.albedo.empty();
  if (!o.brdf.empty() && !transfer::is_glossy(options.kind))
    fail("--brdf applies to glossy transfer only (--transfer glossy-shadowed or glossy-interreflected)");
  // Glossy kinds without --brdf take the mesh's materials (bake_vertices checks that it has some).
  options.brdf_from_mesh = transfer::is_glossy(options.kind) && (o.brdf.empty() || o.brdf == "mesh");
  if (!o.brdf.empty() && !options.brdf_from_mesh) options.brdf = brdf::parse_brdf(o.brdf);
  options.bands_out = o.bands_out;
  const bool ship = ships_compressed(o, options);
  if (o.bands == 0) options.bands = ship ? compress::kHighBands : compress::kShipBands;
  bake::validate_options(options);
  pipeline::TransferOutputs out;
  out.transfer_path = o.output;
  out.gltf_path = o.gltf_output;
  out.source_path = o.mesh_path;
  out.float16 = o.float16 || ship;
  out.seed = o.seed;
  out.threads = o.threads;
  if (!o.compress.empty() && !parse_compress_setting(o.compress, out.clusters, out.pca))
    fail("--compress: expected K,N (clusters, PCA vectors), got '" + o.compress + "'");
  if (o.denoise && o.lightmap.empty()) fail("--denoise applies to lightmap bakes only (give --lightmap SIZE)");
  if (o.stitch && o.lightmap.empty()) fail("--stitch applies to lightmap bakes only (give --lightmap SIZE)");
  if (o.lightmap.empty() && o.uv != "file") fail("--uv applies to texel bakes only (--lightmap SIZE)");
  if (o.lightmap.empty() && o.texel_parts != "all") fail("--texel-parts applies to texel bakes only (--lightmap SIZE)");
  if (o.lightmap.empty())
    bake_vertices(o, options, out);
  else
    bake_texels(o, options, out);
}

}  // namespace

void add_bake_command(CLI::App& app) {
  auto options = std::make_shared<BakeCommandOptions>();
  CLI::App* cmd = app.add_subcommand("bake", "Bake per-vertex PRT transfer (diffuse vectors or glossy matrices) for a mesh (.obj, .ply, .gltf, .glb)");
  cmd->add_option("MESH", options->mesh_path, "Input mesh")->required();
  add_scene_option(cmd, options->scene);
  cmd->add_option("-o,--output", options->output, "Output transfer file (.prt)")->required();
  cmd->add_option("--transfer", options->kind,
                  "unshadowed | shadowed | interreflected | glossy-shadowed | glossy-interreflected")->capture_default_str();
  cmd->add_option("--brdf", options->brdf,
                  "Glossy kinds: the mesh's BRDF: mesh (the default when the file has materials: each glTF material's metallic-roughness "
                  "factors as its own BRDF), or e.g. phong:exponent=32,ks=0.5,kd=0.3 or ggx:roughness=0.3,f0=0.04,albedo=0.5 "
                  "or a .json material (see prt brdf)");
  cmd->add_option("--bands-out", options->bands_out,
                  "Glossy kinds: bands of the transferred radiance (matrix rows), 1..--bands; default --bands");
  cmd->add_option("--bands", options->bands,
                  "SH bands of the lighting (1..32; 5 = 25 coefficients). Default 5, and 16 for a diffuse bake (per vertex or --lightmap) to a .cprt "
                  "without --compress (bake high, ship light: CPCA-compressed to the size and run-time cost of 5 bands)");
  cmd->add_option("--samples", options->samples, "Rays per vertex (shadowed, interreflected)")->capture_default_str();
  cmd->add_option("--bounces", options->bounces,
                  "Interreflection passes; default: until a pass adds < 1e-3 of the direct pass's energy (max 16)");
  cmd->add_option("--albedo", options->albedo, "R,G,B linear albedo for meshes without colours (default 0.8,0.8,0.8)");
  cmd->add_option("--seed", options->seed, "Seed of the sample set and per-vertex frames")->capture_default_str();
  add_footprint_option(cmd, options->footprint,
                       "where a vertex's rays leave from: points of its one-ring, hat-weighted (the value its interpolation "
                       "stands for: no dark vertex under a fold or where objects touch), or the vertex itself (as prt reference per vertex)");
  cmd->add_option("--threads", options->threads, "Worker threads (0 = all cores); output does not depend on it")
      ->capture_default_str();
  cmd->add_option("--gltf", options->gltf_output, "Also write the engine glTF (.glb): the source scene as authored with the transfer (per vertex: clustered PCA, the PRT_transfer extension; per texel: KTX2 textures)");
  cmd->add_flag("--float16", options->float16, "Store the transfer as IEEE float16");
  cmd->add_option("--compress", options->compress,
                  "K,N: compress with clustered PCA (K clusters, N PCA vectors; see prt compress) and write -o as a .cprt file (per vertex or, with --lightmap, per texel). "
                  "Default for a diffuse per-vertex -o T.cprt: 16 bands, K = vertices/256 in 1..64, N <= 24 sized to the 5-band file, float16");
  cmd->add_option("--lightmap", options->lightmap,
                  "WxH or SIZE: bake transfer per texel of the mesh's lightmap UVs (glTF TEXCOORD_1, else TEXCOORD_0; OBJ vt) "
                  "instead of per vertex (diffuse kinds)");
  cmd->add_option("--uv", options->uv,
                  "--lightmap: which lightmap UVs: file (the file's, refused beyond a few defects), auto (the file's when usable, "
                  "else generated as by prt unwrap) or generate")
      ->capture_default_str();
  cmd->add_option("--texel-parts", options->texel_parts,
                  "--lightmap: which parts (glTF primitives, by node name) are baked per texel, the rest per vertex in the same "
                  "bake: all, auto (parts the lightmap gives more texels than they have vertices) or NAME,NAME; a mixed scene "
                  "writes -o (texels) and <stem>.vertices.prt (vertices), and with generated UVs <stem>.mesh.glb, the mesh to render them with")
      ->capture_default_str();
  cmd->add_option("--gutter", options->gutter, "--lightmap: gutter (chart dilation) in texels, 0..64")->capture_default_str();
  cmd->add_flag("--no-sample-repair", options->no_repair,
                "--lightmap: keep texel samples that lie inside geometry where they are (default: move them out)");
  cmd->add_flag("--denoise", options->denoise,
                "--lightmap: filter the baked transfer coefficients with an edge-aware a-trous filter guided by position, normal, "
                "chart and the transfer's own DC term (one denoised bake serves every lighting); e.g. --samples 128 --denoise");
  cmd->add_flag("--stitch", options->stitch,
                "--lightmap: make the texels on the two sides of every smooth UV seam agree under bilinear lookup (least squares "
                "over the texels the lookups read, after --denoise)");
  cmd->add_flag("-q,--quiet", options->quiet, "No progress bar or summary");
  cmd->callback([options] { run_bake(*options); });
}

}  // namespace prt::cli
