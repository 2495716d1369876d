#include "render/headless_render.h"
#include "render/renderer_cpca.h"

#include <chrono>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "core/error.h"
#include "core/text.h"
#include "render/headless_context.h"
#include "render/mixed_frame.h"
#include "render/scene_inputs.h"
#include "sh/rotation.h"
#include "shade/surface_albedo.h"

namespace prt::render {

namespace {

glm::dmat3 rotation_of(const glm::dvec3& ypr) { return sh::rotation_from_yaw_pitch_roll(ypr.x, ypr.y, ypr.z); }

}  // namespace

void check_output_extension(const std::string& path) {
  const std::string extension = lower_extension(path);
  if (extension != ".png" && extension != ".exr")
    fail_file(path, "output must be .png (tone mapped) or .exr (linear radiance)");
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  std::error_code error;
  if (!folder.empty() && !std::filesystem::is_directory(folder, error))
    fail_file(path, "output folder does not exist");
}

void render_to_file(const RenderOptions& options) {
  check_output_extension(options.output);
  // A mixed pair (mixed_frame.h) loads both files: the texel one first.
  const SceneInputs scene = load_scene(options.mesh_path, mixed_transfer_paths(options.transfer_path), options.scene);
  const bool mixed = scene.transfers.size() == 2;
  const TriangleRuns vertex_runs = mixed ? mixed_vertex_runs(scene) : TriangleRuns{};
  const int transfer_bands = static_cast<int>(scene.transfers[0].header.bands);
  // The lighting is projected (and windowed) at the bands the frame shades: the run-time truncation.
  const int shaded_bands = used_bands(scene.transfers[0].header, options.bands);  // before any GL work
  light::WindowRequest window = options.window;
  window.radiance = transfer::is_glossy(scene.transfers[0].header.kind);  // the glossy criterion (light/deringing.h)
  const Lighting lighting = load_render_lighting(options.environment, shaded_bands, options.sun, window);
  const Background background =
      options.background.value_or(lighting.has_image ? Background::environment : Background::sh);
  if (background == Background::environment && !lighting.has_image)
    fail_file_option(options.environment, "background", " env needs an environment image, this is an SH lighting file");

  // Glossy transfer: its BRDFs (one per vertex from a --brdf mesh bake, or --brdf's for all), before any GL work.
  std::optional<brdf::VertexBrdfs> glossy;
  if (transfer::is_glossy(scene.transfers[0].header.kind))
    glossy = glossy_brdfs(scene.transfers[0], scene.transfer_paths[0], options.brdf);
  else if (!options.brdf.empty())
    fail_file_option(scene.transfer_paths[0], "brdf", " applies to glossy transfer; this one is " +
                                           std::string(transfer::kind_name(scene.transfers[0].header.kind)));

  HeadlessContext context;
  Renderer renderer;
  renderer.set_mesh(scene.mesh);
  const int index = add_scene_transfer(renderer, scene, 0);
  if (glossy) renderer.set_brdfs(index, *glossy);
  std::vector<int> indices{index};
  for (std::size_t i = 0; i < scene.transfers.size(); ++i) {
    if (i > 0) indices.push_back(add_scene_transfer(renderer, scene, i));
    if (!lighting.discs.empty() && !glossy)
      renderer.set_surface_albedo(indices[i], shade::surface_albedo(scene.mesh, scene.transfers[i].header, scene.transfer_paths[i]));
  }
  renderer.set_lighting(lighting.coefficients, lighting.has_image ? &lighting.equirect : nullptr);
  renderer.set_discs(lighting.discs);

  FrameSettings settings;
  settings.transfer = mixed ? renderer.add_mixed(indices[0], indices[1], vertex_runs) : index;  // one frame either way
  settings.camera = options.camera;
  settings.environment_rotation = rotation_of(options.rotate);
  settings.object_rotation = rotation_of(options.object_rotate);
  settings.bands = options.bands;
  settings.background = background;
  const auto start = std::chrono::steady_clock::now();
  renderer.render(settings, options.width, options.height);
  const image::Image radiance = renderer.read_radiance();
  const double milliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();

  if (lower_extension(options.output) == ".exr") {
    image::write(options.output, radiance);
  } else {
    image::write(options.output, image::to_display(radiance, options.exposure, options.tone_map));
  }
  if (!options.quiet)
    std::fprintf(stderr, "prt render: %s: %dx%d, %d bands, %s background, %.1f ms on %s; %s\n", options.output.c_str(),
                 options.width, options.height, options.bands > 0 ? options.bands : transfer_bands,
                 background_name(background), milliseconds, context.description().c_str(), lighting.description.c_str());
}

}  // namespace prt::render
