// prt reference: the path-traced ground truth (src/reference), per vertex (a colour PLY) or, with
// --image, as an image seen by the camera of `prt render` (EXR linear radiance or tone-mapped PNG).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include "brdf/brdf.h"
#include "camera/camera.h"
#include "cli/arguments.h"
#include "cli/cmd_reference_texels.h"
#include "cli/output_paths.h"
#include "cli/commands.h"
#include "cli/distributed.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/memory_check.h"
#include "core/text.h"
#include "image/image.h"
#include "light/environment.h"
#include "mesh/mesh.h"
#include "mesh/writers.h"
#include "reference/glossy_estimator.h"
#include "reference/reference.h"
#include "reference/reference_image.h"
#include "sh/basis.h"
#include "sh/rotation.h"

namespace prt::cli {

namespace {

struct ReferenceCommandOptions {
  std::string mesh_path, env, output, albedo;
  int scene = mesh::kDefaultScene;
  std::string brdf, eye;  // glossy: the mesh's BRDF and the eye point
  int brdf_bands = 0;
  int bounces = 0;
  int samples = reference::kDefaultSamples;
  int band_limit = 0;
  unsigned seed = 1;
  int threads = 0;
  bool quiet = false;
  std::string footprint = "area";  // as prt bake's default (docs/conventions.md "Vertex footprint")
  // --image and the options that only it takes (as `prt render`'s).
  bool image = false;
  std::string texels;  // a lightmap (.prt): the reference at its texel sample points (cmd_reference_texels.h)
  std::string camera = "auto", size = "1024x1024", rotate, object_rotate, background = "env", tone_map = "aces";
  double exposure = 0.0;
};

// Which options were given on the command line (CLI11 counts).
struct GivenOptions {
  bool band_limit = false, samples = false, brdf_bands = false;
  std::vector<std::string> image_only;  // names of image-only options that were given
};

void print_summary(const char* what, std::size_t count, int samples, int bounces, const reference::ReferenceReport& report,
                   const std::string& output) {
  const double seconds = std::max(1e-9, report.seconds_trace);
  std::fprintf(stderr,
               "prt reference: %zu %s, %d paths each, %d bounce(s), %llu rays in %.2f s (%.3g Mpaths/s, %.3g Mrays/s), "
               "mean relative standard error %.2g%s -> %s\n",
               count, what, samples, bounces, static_cast<unsigned long long>(report.rays), seconds,
               report.paths / 1e6 / seconds, report.rays / 1e6 / seconds, report.mean_relative_standard_error,
               job_summary().c_str(), output.c_str());
}

reference::ReferenceOptions diffuse_options(const ReferenceCommandOptions& o, const GivenOptions& given) {
  reference::ReferenceOptions options;
  options.bounces = o.bounces;
  options.samples = given.samples ? o.samples : (o.image ? reference::kDefaultImageSamples : reference::kDefaultSamples);
  options.seed = o.seed;
  options.footprint = mesh::parse_footprint(o.footprint, "--footprint");
  options.threads = o.threads;
  options.progress = want_progress(o.quiet) && job().is_root();
  options.dist = &job();
  if (!o.albedo.empty()) options.albedo = glm::vec3(parse_triple(o.albedo, "--albedo", "R,G,B in [0,1]"));
  reference::check_options(options);
  if (given.band_limit && (o.band_limit < 1 || o.band_limit > sh::kMaxBands))
    fail("--band-limit: expected a band count in 1.." + std::to_string(sh::kMaxBands) + ", got " +
         std::to_string(o.band_limit));
  return options;
}

// The glossy options (--brdf, --eye, --brdf-bands), checked; `options` gives the shared ones.
reference::GlossyReferenceOptions glossy_options(const ReferenceCommandOptions& o, const GivenOptions& given,
                                                 const reference::ReferenceOptions& options) {
  reference::GlossyReferenceOptions glossy = reference::glossy_run_options(options);
  if (o.brdf.empty()) fail(o.eye.empty() ? "--brdf-bands needs --brdf SPEC" : "--eye needs --brdf SPEC (glossy reference)");
  if (o.eye.empty()) fail("--brdf needs --eye X,Y,Z: glossy radiance depends on the view");
  if (o.image) fail("--brdf: the glossy reference is per vertex only (no --image)");
  if (!o.albedo.empty()) fail("--albedo does not apply with --brdf (the BRDF is the material)");
  glossy.estimator.brdf = brdf::parse_brdf(o.brdf);
  glossy.estimator.bounces = options.bounces;
  if (given.brdf_bands && (o.brdf_bands < 1 || o.brdf_bands > sh::kMaxBands))
    fail("--brdf-bands: expected a band count in 1.." + std::to_string(sh::kMaxBands) + ", got " + std::to_string(o.brdf_bands));
  glossy.estimator.brdf_bands = given.brdf_bands ? o.brdf_bands : 0;
  glossy.eye = parse_triple(o.eye, "--eye", "X,Y,Z (mesh units)");
  return glossy;
}

// The --image options (camera, size, rotations, background, exposure, tone map), checked.
reference::ImageOptions image_options(const ReferenceCommandOptions& o, const std::string& extension) {
  reference::ImageOptions image;
  if (extension != ".exr" && extension != ".png")
    fail_file(o.output, "--image output must be .exr (linear radiance) or .png (tone mapped)");
  image.camera = camera::parse_camera(o.camera);
  camera::parse_size(o.size, image.width, image.height);
  // Per pixel: the radiance, standard error and coverage the tracer fills, the image written from
  // them and the encoder's copy: at most 64 bytes.
  const std::uint64_t pixels = std::uint64_t(image.width) * std::uint64_t(image.height);
  check_memory_need("size", o.size, saturating_product(pixels, 64));
  if (!o.rotate.empty()) {
    const glm::dvec3 a = parse_angles(o.rotate, "--rotate");
    image.environment_rotation = sh::rotation_from_yaw_pitch_roll(a.x, a.y, a.z);
  }
  if (!o.object_rotate.empty()) {
    const glm::dvec3 a = parse_angles(o.object_rotate, "--object-rotate");
    image.object_rotation = sh::rotation_from_yaw_pitch_roll(a.x, a.y, a.z);
  }
  if (o.background != "env" && o.background != "black")
    fail("--background: expected env or black, got '" + o.background +
         "' (the reference has no SH background: with --band-limit N the environment itself is band-limited)");
  image.black_background = o.background == "black";
  if (!std::isfinite(o.exposure)) fail("--exposure: must be a finite number of stops");
  parse_tone_map(o.tone_map);
  return image;
}

void write_reference_image(const ReferenceCommandOptions& o, const reference::ReferenceImage& result,
                           const reference::ImageOptions& image, const std::string& extension) {
  if (extension == ".exr") {
    image::write(o.output, result.radiance);
  } else {
    image::write(o.output, image::to_display(result.radiance, o.exposure, parse_tone_map(o.tone_map)));
  }
  if (o.quiet) return;
  const std::size_t covered = static_cast<std::size_t>(std::count(result.covered.begin(), result.covered.end(), 1));
  const std::string what = "covered pixels of " + std::to_string(image.width) + "x" + std::to_string(image.height);
  print_summary(what.c_str(), covered, image.reference.samples, image.reference.bounces, result.report, o.output);
}

// Everything of the command line that changes the output (dist: every rank must trace the same job).
std::string canonical_options(const ReferenceCommandOptions& o, const reference::ReferenceOptions& r) {
  std::string text = "reference bounces " + std::to_string(r.bounces) + " samples " + std::to_string(r.samples) +
                     " seed " + std::to_string(r.seed) + " footprint " + mesh::footprint_name(r.footprint) + " albedo " + exact(r.albedo.r) + "," + exact(r.albedo.g) + "," +
                     exact(r.albedo.b) + " band-limit " + std::to_string(o.band_limit) + " brdf " +
                     (o.brdf.empty() ? "" : brdf::to_spec(brdf::parse_brdf(o.brdf))) + " brdf-bands " +
                     std::to_string(o.brdf_bands) + " eye " + o.eye + " image " + std::to_string(o.image);
  if (o.image)
    text += " camera " + o.camera + " size " + o.size + " rotate " + o.rotate + " object-rotate " + o.object_rotate +
            " background " + o.background + " exposure " + exact(o.exposure) + " tone-map " + o.tone_map;
  return text;
}

void run_reference(const ReferenceCommandOptions& o, const GivenOptions& given) {
  // Everything the arguments can get wrong is checked before loading and tracing for minutes.
  const reference::ReferenceOptions options = diffuse_options(o, given);
  const bool glossy = !o.brdf.empty();
  reference::GlossyReferenceOptions glossy_reference;
  if (glossy || !o.eye.empty() || given.brdf_bands) glossy_reference = glossy_options(o, given, options);
  const std::string extension = lower_extension(o.output);
  reference::ImageOptions image;
  if (!o.texels.empty()) {
    if (o.image || glossy) fail("--texels: the texel reference is diffuse, without --image");
    if (extension != ".exr") fail_file(o.output, "--texels output must be .exr (linear radiance per texel)");
  } else if (o.image) {
    image = image_options(o, extension);
  } else {
    if (!given.image_only.empty()) fail(given.image_only.front() + " is an option of --image");
    if (extension != ".ply")
      fail_file(o.output, extension == ".exr" || extension == ".png" ? "an image output needs --image"
                                                                     : "output must be .ply (or .exr/.png with --image)");
  }
  if (job().is_root()) check_outputs({o.output}, {o.mesh_path, o.env, o.brdf, o.texels});  // rank 0 alone writes

  const mesh::Mesh mesh = load_mesh_for_albedo(o.mesh_path, o.albedo, {o.scene, o.quiet || !job().is_root()}, nullptr);
  light::Environment environment = light::load_environment(o.env);
  check_job_inputs({mesh_input(o.mesh_path, mesh), environment_input(o.env, environment),
                    options_input(canonical_options(o, options))});
  std::optional<light::Environment> loaded;  // shown behind the mesh when the lighting is band-limited
  if (given.band_limit) {
    light::Environment limited = reference::band_limited_environment(environment, o.band_limit, o.threads);
    if (o.image) loaded = std::move(environment);
    environment = std::move(limited);
  }
  const reference::EnvironmentSampler sampler(std::move(environment));

  if (!o.texels.empty()) {
    run_reference_texels(mesh, o.mesh_path, sampler, options, o.texels, o.output, o.quiet);
    return;
  }
  if (!o.image) {
    reference::ReferenceReport report;
    const std::vector<glm::vec3> radiance = glossy ? reference::glossy_vertex_radiance(mesh, sampler, glossy_reference, &report)
                                                   : reference::vertex_radiance(mesh, sampler, options, &report);
    if (!job().is_root()) return;  // only rank 0 holds the whole result
    mesh::write_ply(o.output, mesh.positions, radiance, mesh.indices);
    if (!o.quiet) print_summary("vertices", mesh.positions.size(), options.samples, options.bounces, report, o.output);
    return;
  }
  image.reference = options;
  const reference::ReferenceImage result = reference::render_image(mesh, sampler, image, loaded ? &*loaded : nullptr);
  if (!job().is_root()) return;
  write_reference_image(o, result, image, extension);
}

}  // namespace

void add_reference_command(CLI::App& app) {
  auto options = std::make_shared<ReferenceCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "reference",
      "Path-traced ground truth: per-vertex outgoing radiance under an environment as a colour PLY, or with --image "
      "the image `prt render` would show (EXR linear radiance, PNG tone mapped)");
  cmd->add_option("MESH", options->mesh_path, "Input mesh (.obj, .ply, .gltf, .glb)")->required();
  add_scene_option(cmd, options->scene);
  cmd->add_option("--env", options->env, "Environment image (equirect 2:1, cross, or six faces)")->required();
  cmd->add_option("--bounces", options->bounces,
                  "Interreflection bounces (0 = direct light with visibility, as --transfer shadowed)")
      ->capture_default_str();
  CLI::Option* samples = cmd->add_option(
      "--samples,--spp", options->samples,
      "Paths per vertex (default " + std::to_string(reference::kDefaultSamples) + "), or per covered pixel with --image "
      "(default " + std::to_string(reference::kDefaultImageSamples) + ")");
  cmd->add_option("--albedo", options->albedo, "R,G,B linear albedo for meshes without colours (default 0.8,0.8,0.8)");
  CLI::Option* band_limit = cmd->add_option(
      "--band-limit", options->band_limit,
      "Replace the environment by its reconstruction from its first N SH bands (signed), to compare with a bake of N bands");
  cmd->add_option("--brdf", options->brdf,
                  "Glossy reference: the mesh's BRDF (as prt brdf / prt bake --brdf); radiance toward --eye per vertex");
  cmd->add_option("--eye", options->eye, "Glossy reference: X,Y,Z eye point (mesh units)");
  CLI::Option* brdf_bands = cmd->add_option(
      "--brdf-bands", options->brdf_bands,
      "Glossy reference: use the BRDF's band-limited reconstruction from N SH bands (signed), to compare with a glossy "
      "bake whose output bands are N");
  cmd->add_option("--seed", options->seed, "Seed of the per-vertex (per-pixel) random streams")->capture_default_str();
  cmd->add_option("--threads", options->threads, "Worker threads (0 = all cores); output does not depend on it")
      ->capture_default_str();
  cmd->add_flag("-q,--quiet", options->quiet, "No progress bar or summary");
  add_footprint_option(cmd, options->footprint,
                       "per-vertex output: the hat-weighted average over each vertex's one-ring (as prt bake --footprint "
                       "area stores) or the radiance exactly at the vertex");
  cmd->add_option("--texels", options->texels,
                  "LIGHTMAP.prt (prt bake --lightmap): the reference at its texel sample points, as an .exr of the lightmap's "
                  "size (covered texels; others 0)");
  cmd->add_flag("--image", options->image,
                "Render an image from the camera of `prt render`: one ray per pixel centre, the outgoing radiance at "
                "the hit (--samples paths), the environment (or black) behind");
  std::vector<CLI::Option*> image_only = {
      cmd->add_option("--camera", options->camera,
                      "--image: AZ,EL,DIST or auto, orbit about the bounds centre (as prt render)")
          ->capture_default_str(),
      cmd->add_option("--size", options->size, "--image: WxH pixels")->capture_default_str(),
      cmd->add_option("--rotate", options->rotate, "--image: YAW,PITCH,ROLL degrees: rotate the environment by Ry Rx Rz"),
      cmd->add_option("--object-rotate", options->object_rotate,
                      "--image: YAW,PITCH,ROLL degrees: rotate the object about its bounds centre"),
      cmd->add_option("--background", options->background, "--image: env (the environment) or black")
          ->capture_default_str(),
      cmd->add_option("--exposure", options->exposure, "--image: exposure in stops (PNG only)")->capture_default_str(),
      cmd->add_option("--tone-map", options->tone_map, "--image: aces (Narkowicz 2015) or clamp (PNG only)")
          ->capture_default_str(),
  };
  cmd->add_option("-o,--output", options->output,
                  "Output .ply (float x,y,z,red,green,blue, faces); with --image .exr (linear) or .png (tone mapped)")
      ->required();
  cmd->callback([options, band_limit, samples, image_only, brdf_bands] {
    GivenOptions given;
    given.band_limit = band_limit->count() > 0;
    given.brdf_bands = brdf_bands->count() > 0;
    given.samples = samples->count() > 0;
    for (const CLI::Option* option : image_only)
      if (option->count() > 0) given.image_only.push_back(option->get_name());
    run_reference(*options, given);
  });
}

}  // namespace prt::cli
