#pragma once
// `prt view`: the interactive relighting viewer (GLFW window, OpenGL 4.5 core, Dear ImGui panel).
//
// CONTROLS (keys are ignored while the panel has keyboard focus, mouse input while over the panel)
//   left drag               orbit the camera (azimuth, elevation)
//   Shift + left drag,
//   or right drag           rotate the lighting (horizontal: yaw, vertical: pitch)
//   Ctrl + left drag,
//   or middle drag          rotate the object (horizontal: yaw, vertical: pitch)
//   scroll                  zoom (distance x 0.9 per notch)
//   1 .. 9                  choose the transfer (when several are loaded)
//   [  ]                    use one band fewer / more (truncation to the first k bands)
//   -  =                    exposure -/+ 0.5 stops
//   E, Shift + E            next / previous environment
//   B                       background: env -> sh -> black
//   L                       shading: PRT <-> Lambert baseline
//   U                       sun on / off: the discs (--sun) shaded exactly with shadow maps, or the sky
//                           alone; the panel shows each disc's direction, radius and irradiance E
//   G                       glossy transfer: the full BRDF <-> its diffuse (lambert) lobes only; the
//                           panel also edits each lobe's parameters live (B re-projected on the CPU)
//   T                       tone map: ACES <-> clamp
//   R                       reset camera, lighting rotation and object rotation
//   S                       screenshot: prt-view-NNN.png (as shown, without the panel) and prt-view-NNN.exr
//                           (linear radiance) in the current folder, NNN the first unused number
//   H                       hide / show the panel
//   Esc, Q                  quit
// Dropping files on the window loads each as an environment (image, or SH lighting .json) and selects it.
// The panel (narrow, collapsible by its title bar) shows frame time (CPU, averaged) and GPU render time (timer query) and every control above.
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "image/image.h"
#include "light/scene_lighting.h"
#include "mesh/mesh.h"
#include "render/renderer.h"

namespace prt::render {

struct ViewerOptions {
  std::string mesh_path;
  int scene = mesh::kDefaultScene;  ///< mesh::LoadOptions::scene
  /// One or more, all for the mesh (diffuse or glossy). A file of a mixed pair (mixed_frame.h) loads
  /// both files and adds, after all files, an entry drawing the pair in one frame; the viewer starts on
  /// it when the first file given is of a pair.
  std::vector<std::string> transfer_paths;
  std::string brdf;                         ///< glossy transfers: BRDF SPEC; empty = each one's baked BRDF
  std::vector<std::string> environments;    ///< one or more (images or SH lighting .json)
  Camera camera;
  glm::dvec3 rotate{0.0};         ///< initial environment yaw, pitch, roll (degrees)
  glm::dvec3 object_rotate{0.0};  ///< initial object yaw, pitch, roll (degrees)
  double exposure = 0.0;          ///< stops
  image::ToneMap tone_map = image::ToneMap::aces;
  std::optional<Background> background;  ///< default: env if the first environment is an image, else sh
  int bands = 0;                  ///< initial truncation; 0 = all
  light::SunRequest sun;          ///< --sun for every environment (default auto)
  light::WindowRequest window;    ///< --window for every environment (default auto)
  int width = 1280, height = 800; ///< window size in screen coordinates
  int frames = 0;                 ///< > 0: render this many frames, then exit (scripted runs)
  std::string screenshot;         ///< with frames: save the last frame here (.png tone mapped or .exr linear)
};

/// Loads everything (throwing prt::Error("<file>: <problem>") before any window opens), opens the
/// window and runs until it is closed (or `frames` frames are drawn). Throws prt::Error if GLFW cannot
/// open a window with an OpenGL 4.5 core context. Everything is released on return, also on errors.
void run_viewer(const ViewerOptions& options);

}  // namespace prt::render
