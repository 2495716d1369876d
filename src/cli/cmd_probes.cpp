// prt probes: bakes SH light probes in a scene (src/probes) and exports them for an engine.
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <cstring>
#include <sstream>

#include "cli/arguments.h"
#include "cli/output_paths.h"
#include "cli/commands.h"
#include "cli/distributed.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/memory_check.h"
#include "light/environment.h"
#include "light/scene_lighting.h"
#include "light/sun_extraction.h"
#include "mesh/mesh.h"
#include "probes/baker.h"
#include "probes/exporters.h"
#include "probes/lighting.h"

namespace prt::cli {

namespace {

struct ProbesCommandOptions {
  std::string scene_path;
  int scene = mesh::kDefaultScene;
  std::string environment;
  std::string sun = "auto";
  std::string grid;
  std::string bounds;
  std::string points;
  std::string format;
  std::string output;
  std::string albedo;
  std::string probe = "sky";
  int specular_size = 64;
  probes::ProbeBakeOptions bake;
  bool transfer = false;
  bool quiet = false;
};

std::vector<double> parse_numbers(const std::string& text, std::size_t count, const std::string& option, const std::string& what) {
  std::vector<double> values;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (item.empty() || end == item.c_str() || *end != '\0' || !std::isfinite(v))
      fail(option + ": expected " + what + ", got '" + text + "'");
    values.push_back(v);
  }
  if (values.size() != count || (!text.empty() && text.back() == ',')) fail(option + ": expected " + what + ", got '" + text + "'");
  return values;
}

std::string describe_point(const glm::vec3& p) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%g, %g, %g)", p.x, p.y, p.z);
  return buf;
}

// The probe layout of --grid (with --bounds, or bounds to follow from the scene) or --points, checked.
probes::ProbeSet parse_layout(const ProbesCommandOptions& o) {
  if (o.grid.empty() == o.points.empty()) fail("give exactly one of --grid NX,NY,NZ and --points FILE");
  if (!o.bounds.empty() && o.grid.empty()) fail("--bounds needs --grid");
  probes::ProbeSet layout;
  if (o.grid.empty()) return layout;
  const std::vector<double> counts = parse_numbers(o.grid, 3, "--grid", "NX,NY,NZ");
  for (int a = 0; a < 3; ++a) {
    if (counts[a] != std::floor(counts[a]) || counts[a] < 0 || counts[a] > (1 << 26))
      fail("--grid: counts must be whole numbers >= 1, got '" + o.grid + "'");
    layout.grid.counts[a] = static_cast<int>(counts[a]);
  }
  layout.layout = probes::ProbeSet::Layout::grid;
  if (!o.bounds.empty()) {
    const std::vector<double> b = parse_numbers(o.bounds, 6, "--bounds", "X0,Y0,Z0,X1,Y1,Z1");
    layout.grid.lo = {b[0], b[1], b[2]};
    layout.grid.hi = {b[3], b[4], b[5]};
  } else {
    layout.grid.lo = glm::dvec3(1.0);  // bounds follow from the scene later; check the counts now
    layout.grid.hi = glm::dvec3(2.0);
  }
  probes::check_grid(layout.grid);
  return layout;
}

// The probe positions: the grid's cell centres (its bounds the scene's unless given), or the --points
// positions, checked to lie inside the scene's bounds.
std::vector<glm::dvec3> place_probes(const ProbesCommandOptions& o, const mesh::Mesh& mesh, probes::ProbeSet& layout,
                                     std::vector<glm::dvec3> points) {
  const mesh::Bounds scene_bounds = mesh::bounds(mesh);
  if (layout.layout != probes::ProbeSet::Layout::grid) {
    probes::check_points_inside(points, glm::dvec3(scene_bounds.lo), glm::dvec3(scene_bounds.hi), o.points);
    return points;
  }
  if (o.bounds.empty()) {
    layout.grid.lo = glm::dvec3(scene_bounds.lo);
    layout.grid.hi = glm::dvec3(scene_bounds.hi);
    try {
      probes::check_grid(layout.grid);
    } catch (const Error& e) {
      fail_file(o.scene_path, std::string("the scene's bounds cannot hold a grid (") + e.what() + "); give --bounds");
    }
  }
  return probes::grid_positions(layout.grid);
}

void print_summary(const ProbesCommandOptions& o, const probes::ProbeSet& baked, const probes::ProbeBakeReport& report,
                   probes::Format format, double seconds) {
  if (report.invalid > 0) {
    std::string list;
    std::size_t shown = 0;
    for (std::size_t i = 0; i < baked.count() && shown < 8; ++i)
      if (!baked.valid[i]) list += (shown++ ? ", " : "") + std::to_string(i) + " " + describe_point(baked.positions[i]);
    if (report.invalid > shown) list += ", ...";
    std::fprintf(stderr, "prt probes: %zu of %zu probes are inside geometry (more than %.0f%% back-face hits), marked invalid: %s\n",
                 report.invalid, baked.count(), 100.0 * o.bake.max_backface_fraction, list.c_str());
  }
  std::fprintf(stderr, "prt probes: %zu probes, %d bands, %d rays each, %d bounce(s)%s, %.2f Mrays in %.2f s%s -> %s (%s)\n",
               baked.count(), baked.bands, o.bake.rays, o.bake.bounces, o.bake.transfer_bands ? ", with transfer" : "",
               (report.surface_rays + report.probe_rays + report.transfer_rays) / 1e6, seconds, job_summary().c_str(),
               o.output.c_str(),
               probes::format_name(format));
}

// Everything of the command line that changes the output (dist: every rank must bake the same job).
std::string canonical_options(const ProbesCommandOptions& o) {
  const probes::ProbeBakeOptions& b = o.bake;
  return "probes bands " + std::to_string(b.bands) + " rays " + std::to_string(b.rays) + " bounces " +
         std::to_string(b.bounces) + " surface " + std::to_string(b.surface_samples) + " sun-samples " +
         std::to_string(b.sun_samples) + " backface " + exact(b.max_backface_fraction) + " transfer " +
         std::to_string(b.transfer_bands) + " albedo " + exact(b.albedo.r) + "," + exact(b.albedo.g) + "," +
         exact(b.albedo.b) + " seed " + std::to_string(b.seed) + " sun " + o.sun + " grid " + o.grid + " bounds " +
         o.bounds + " format " + o.format + " probe " + o.probe + " specular " + std::to_string(o.specular_size);
}

// Fingerprint of the probe positions (named by the points file, or the grid).
dist::Fingerprint positions_input(const ProbesCommandOptions& o, const std::vector<glm::dvec3>& positions) {
  std::string bytes(positions.size() * sizeof(glm::dvec3), '\0');
  if (!positions.empty()) std::memcpy(&bytes[0], positions.data(), bytes.size());
  return {o.points.empty() ? "the probe grid" : o.points, dist::fingerprint_of(bytes)};
}

void run_probes(ProbesCommandOptions o) {
  const probes::Format format = probes::parse_format(o.format);
  probes::ProbeSet layout = parse_layout(o);
  if (format == probes::Format::bevy && layout.layout != probes::ProbeSet::Layout::grid)
    fail("--format bevy needs a probe grid (--grid): an irradiance volume is a 3D texture");
  if (!o.albedo.empty()) o.bake.albedo = glm::vec3(parse_triple(o.albedo, "--albedo", "R,G,B in [0,1]"));
  if (o.transfer && o.bake.transfer_bands == 0) o.bake.transfer_bands = o.bake.bands;
  if (!o.transfer) o.bake.transfer_bands = 0;
  o.bake.progress = want_progress(o.quiet) && job().is_root();
  o.bake.dist = &job();
  probes::check_options(o.bake);
  probes::SceneLight light;
  const light::SunRequest sun = light::parse_sun_request(o.sun);
  if (sun.mode == light::SunRequest::Mode::given) light.sun = sun.disc;
  std::vector<glm::dvec3> points;
  if (!o.points.empty()) points = probes::read_points_file(o.points);
  const probes::Grid& g = layout.grid;
  const std::uint64_t count = o.points.empty() ? std::uint64_t(g.counts[0]) * std::uint64_t(g.counts[1]) * std::uint64_t(g.counts[2])
                                               : points.size();
  check_memory_need(o.points.empty() ? "grid" : "points",
                    (o.points.empty() ? o.grid : o.points) + " at --bands " + std::to_string(o.bake.bands) +
                        (o.bake.transfer_bands ? " with --transfer" : ""),
                    probes::estimated_bytes(count, o.bake));
  if (job().is_root()) check_outputs({o.output}, {o.scene_path, o.environment, o.points});  // rank 0 alone writes

  mesh::LoadReport load_report;
  const mesh::Mesh mesh = load_mesh_for_albedo(o.scene_path, o.albedo, {o.scene, o.quiet || !job().is_root()}, &load_report);
  const std::vector<glm::dvec3> positions = place_probes(o, mesh, layout, std::move(points));
  light::Environment environment = light::load_environment(o.environment);
  check_job_inputs({mesh_input(o.scene_path, mesh), environment_input(o.environment, environment),
                    positions_input(o, positions), options_input(canonical_options(o))});
  if (sun.mode == light::SunRequest::Mode::automatic) {
    // The brightest compact source becomes the probes' sun (traced with visibility); the rest stays sky.
    light::ExtractionResult extracted = light::extract_discs(environment, o.bake.threads, 1);
    if (!extracted.discs.empty()) {
      light.sun = extracted.discs.front();
      environment = std::move(extracted.residual);
      if (!o.quiet && job().is_root())
        std::fprintf(stderr, "prt probes: sun found in %s: --sun %s\n", o.environment.c_str(), light::format_disc(*light.sun).c_str());
    }
  }
  light.environment = &environment;
  light.emission = mesh.emission;  // glTF emissiveFactor x emissiveStrength, OBJ/MTL Ke; empty if none

  const auto start = std::chrono::steady_clock::now();
  probes::ProbeBakeReport report;
  const probes::ProbeSet baked = probes::bake_probes(mesh, light, positions, layout, o.bake, &report);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!job().is_root()) return;  // only rank 0 holds the whole result
  probes::ExportOptions export_options;
  export_options.probe = o.probe;
  export_options.scene_path = o.scene_path;
  export_options.environment = &environment;
  export_options.specular_size = o.specular_size;
  probes::export_probes(baked, format, o.output, export_options);
  if (!o.quiet) print_summary(o, baked, report, format, seconds);
}

}  // namespace

void add_probes_command(CLI::App& app) {
  auto o = std::make_shared<ProbesCommandOptions>();
  CLI::App* cmd = app.add_subcommand("probes", "Bake SH light probes in a scene (.gltf, .glb, .obj, .ply) and export them for an engine");
  cmd->add_option("SCENE", o->scene_path, "Scene file")->required();
  add_scene_option(cmd, o->scene);
  cmd->add_option("--env", o->environment, "Environment map (equirect, cross or six faces; see prt light)")->required();
  cmd->add_option("--sun", o->sun,
                  "auto (the map's sun, if it has one, traced as a disc), none, or a disc DX,DY,DZ,R,G,B,RADIUS_DEG "
                  "(or DX,DY,DZ,E,RADIUS_DEG; R,G,B = irradiance at normal incidence) added to the map")
      ->capture_default_str();
  cmd->add_option("--grid", o->grid, "NX,NY,NZ probes at the cell centres of the bounds");
  cmd->add_option("--bounds", o->bounds, "X0,Y0,Z0,X1,Y1,Z1 box of the grid (default: the scene's bounds)");
  cmd->add_option("--points", o->points, "Probe positions: .json ([[x,y,z],...]) or .csv (x,y,z per line)");
  cmd->add_option("--format", o->format, "prt | threejs | unity | godot | filament | gltf | bevy")->required();
  cmd->add_option("-o,--output", o->output, "Output file")->required();
  cmd->add_option("--bands", o->bake.bands, "SH bands per probe (1..16)")->capture_default_str();
  cmd->add_option("--rays", o->bake.rays, "Rays per probe")->capture_default_str();
  cmd->add_option("--bounces", o->bake.bounces, "Interreflection bounces of the surface light (0..64)")->capture_default_str();
  cmd->add_option("--surface-samples", o->bake.surface_samples, "Hemisphere rays per scene vertex")->capture_default_str();
  cmd->add_option("--sun-samples", o->bake.sun_samples, "Shadow rays toward the sun's disc per vertex and probe")->capture_default_str();
  cmd->add_option("--max-backface", o->bake.max_backface_fraction, "Back-face hit fraction above which a probe is invalid")
      ->capture_default_str();
  cmd->add_flag("--transfer", o->transfer, "Also store per-probe transfer matrices (relightable; see prt probes-relight)");
  cmd->add_option("--transfer-bands", o->bake.transfer_bands, "Environment bands of the transfer (default: --bands)");
  cmd->add_option("--albedo", o->albedo, "R,G,B linear albedo for scenes without colours (default 0.8,0.8,0.8)");
  cmd->add_option("--probe", o->probe, "filament: 'sky' or a probe index")->capture_default_str();
  cmd->add_option("--specular-size", o->specular_size, "gltf: edge of the largest specular cube face (power of two)")
      ->capture_default_str();
  cmd->add_option("--seed", o->bake.seed, "Seed of the ray sets and rotations")->capture_default_str();
  cmd->add_option("--threads", o->bake.threads, "Worker threads (0 = all cores); output does not depend on it")->capture_default_str();
  cmd->add_flag("-q,--quiet", o->quiet, "No progress bar or summary");
  cmd->callback([o] { run_probes(*o); });
}

}  // namespace prt::cli
