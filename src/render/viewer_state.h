#pragma once
// Internal to the viewer (viewer.cpp, viewer_panel.cpp): its live state.
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "brdf/brdf.h"
#include "render/renderer.h"
#include "render/scene_inputs.h"
#include "render/viewer.h"

namespace prt::render::viewer_detail {

struct ViewerState {
  // Inputs.
  std::vector<std::string> transfer_names;  ///< one line per transfer for the panel
  std::vector<int> transfer_bands;
  std::vector<brdf::Brdf> transfer_brdfs;   ///< per transfer: its BRDF (empty for diffuse transfers)
  /// Per transfer: its BRDFs when a `--brdf mesh` bake has several (shown as they are, not edited; its
  /// transfer_brdfs entry is the first), else an empty table.
  std::vector<brdf::VertexBrdfs> transfer_tables;
  std::vector<int> transfer_bands_out;      ///< per transfer: output bands (0 for diffuse transfers)
  std::vector<Lighting> environments;
  int projection_bands = 1;                 ///< bands environments are projected to
  light::SunRequest sun_request;            ///< --sun, for dropped environments too
  light::WindowRequest window_request;      ///< --window, for dropped environments too
  std::string renderer_name;
  std::size_t vertex_count = 0, triangle_count = 0;

  // Live controls.
  FrameSettings settings;
  int environment = 0;
  double exposure = 0.0;
  image::ToneMap tone_map = image::ToneMap::aces;
  glm::dvec3 light_angles{0.0};   ///< yaw, pitch, roll in degrees
  glm::dvec3 object_angles{0.0};
  bool show_panel = true;
  bool diffuse_lobes_only = false;  ///< glossy: shade with the BRDF's lambert lobes only (G)

  // Requests from input or the panel, handled by the main loop.
  bool environment_changed = true;
  bool brdf_changed = false;        ///< the current glossy transfer's BRDF (or the G toggle) was edited
  bool screenshot_requested = false;
  bool reset_requested = false;
  std::vector<std::string> dropped;

  // Measurements and messages.
  double frame_ms = 0.0;   ///< CPU time between frames, exponentially averaged
  double render_ms = 0.0;  ///< GPU time of the scene passes (timer query)
  double projection_ms = 0.0;  ///< CPU time of the last BRDF re-projection
  std::string message;

  /// Band count of the current transfer.
  int current_bands() const { return transfer_bands[static_cast<std::size_t>(settings.transfer)]; }
  /// Whether the current transfer is glossy.
  bool current_glossy() const { return !transfer_brdfs[static_cast<std::size_t>(settings.transfer)].empty(); }
  /// The current transfer has one BRDF per vertex (transfer_tables).
  bool current_table() const { return !transfer_tables[static_cast<std::size_t>(settings.transfer)].table.empty(); }
};

/// Draws the Dear ImGui panel and applies its edits to the state. Between ImGui::NewFrame and Render.
void draw_panel(ViewerState& state);

/// Applies one key press (GLFW key code and modifier bits) to the state. Returns true to quit.
bool apply_key(ViewerState& state, int key, int mods);

/// Clamps and normalises the state after edits (bands range, elevation, background availability).
void sanitise(ViewerState& state);

/// The BRDF the current glossy transfer is drawn with: its BRDF, or (diffuse_lobes_only) only its
/// lambert lobes (a lambert lobe of albedo 0.8 if it has none).
brdf::Brdf shown_brdf(const ViewerState& state);

}  // namespace prt::render::viewer_detail
