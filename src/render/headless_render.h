#pragma once
// `prt render`: one frame rendered headless (EGL) and written as an image.
#include <optional>
#include <string>

#include <glm/vec3.hpp>

#include "image/image.h"
#include "light/scene_lighting.h"
#include "mesh/mesh.h"
#include "render/renderer.h"

namespace prt::render {

struct RenderOptions {
  std::string mesh_path;
  int scene = mesh::kDefaultScene;  ///< mesh::LoadOptions::scene
  std::string transfer_path;
  std::string environment;              ///< environment image or SH lighting JSON (see load_render_lighting)
  std::string output;                   ///< .png (tone mapped, 8-bit sRGB) or .exr (linear radiance)
  glm::dvec3 rotate{0.0};               ///< environment yaw, pitch, roll in degrees
  glm::dvec3 object_rotate{0.0};        ///< object yaw, pitch, roll in degrees
  Camera camera;
  int width = 1024, height = 1024;
  double exposure = 0.0;                ///< stops, PNG only
  image::ToneMap tone_map = image::ToneMap::aces;  ///< PNG only
  std::optional<Background> background; ///< default: env for an image, sh for an SH lighting file
  int bands = 0;                        ///< use the first `bands` bands; 0 = all the transfer has
  std::string brdf;                     ///< glossy transfer: BRDF SPEC; empty = the one recorded at bake time
  light::SunRequest sun;                ///< --sun: discs shaded exactly (default auto)
  light::WindowRequest window;          ///< --window for the sky's SH (default auto)
  bool quiet = false;                   ///< no summary line on stderr
};

/// Checks the output's extension (.png or .exr), loads the inputs (checking the transfer against the
/// mesh), renders on a HeadlessContext and writes the output atomically. Throws prt::Error("<file>:
/// <problem>") on any failure, before anything is written. Prints one summary line on stderr unless
/// quiet.
void render_to_file(const RenderOptions& options);

/// Checks that `path` ends in .png or .exr (case-insensitive); throws prt::Error("<path>: ...").
void check_output_extension(const std::string& path);

}  // namespace prt::render
