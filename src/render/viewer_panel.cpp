// The viewer's Dear ImGui panel and key bindings (see the CONTROLS list in viewer.h).
#include <algorithm>
#include <cmath>
#include <filesystem>

#include <glm/common.hpp>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include "render/viewer_state.h"

namespace prt::render::viewer_detail {

namespace {

constexpr double kExposureStep = 0.5;
constexpr double kMaxElevation = 89.0;
constexpr float kPanelWidth = 290.0f;            // narrow: the default framing leaves the object clear
constexpr const char* kLongestLabel = "lambert albedo";

// The sun: on/off (U) and each disc's parameters in the rotated environment's frame, and the window.
void draw_sun_controls(ViewerState& state) {
  const Lighting& lighting = state.environments[static_cast<std::size_t>(state.environment)];
  ImGui::Separator();
  if (lighting.discs.empty()) {
    ImGui::TextDisabled("sun: none");
  } else {
    ImGui::Checkbox("sun, exact with shadows (U)", &state.settings.sun);
    for (const light::Disc& disc : lighting.discs) {
      const glm::dvec3 d = state.settings.environment_rotation * disc.direction;
      ImGui::Text("dir %.3f %.3f %.3f", d.x, d.y, d.z);
      ImGui::Text("radius %.3f deg", disc.angular_radius * 57.29577951308232);
      ImGui::Text("E %.4g %.4g %.4g", disc.irradiance.x, disc.irradiance.y, disc.irradiance.z);
    }
  }
  ImGui::Text("sky window: %s", lighting.window.c_str());
}

// A slider over three doubles shown as floats (ImGui has no double3 slider).
bool slider_angles(const char* label, glm::dvec3& angles) {
  float values[3] = {static_cast<float>(angles.x), static_cast<float>(angles.y), static_cast<float>(angles.z)};
  if (!ImGui::SliderFloat3(label, values, -180.0f, 180.0f, "%.1f")) return false;
  angles = glm::dvec3(values[0], values[1], values[2]);
  return true;
}

// Colour editor over a dvec3 with components in [0, 1].
bool edit_colour(const char* label, glm::dvec3& colour) {
  float values[3] = {static_cast<float>(colour.r), static_cast<float>(colour.g), static_cast<float>(colour.b)};
  if (!ImGui::ColorEdit3(label, values, ImGuiColorEditFlags_Float)) return false;
  colour = glm::clamp(glm::dvec3(values[0], values[1], values[2]), glm::dvec3(0.0), glm::dvec3(1.0));
  return true;
}

// The glossy transfer's BRDF: full or diffuse lobes (G), and each lobe's parameters, edited live.
void draw_brdf_controls(ViewerState& state) {
  if (state.current_table()) {
    ImGui::TextWrapped("BRDFs: %zu, one per material (--brdf mesh; not edited here)",
                       state.transfer_tables[static_cast<std::size_t>(state.settings.transfer)].table.size());
    return;
  }
  brdf::Brdf& brdf = state.transfer_brdfs[static_cast<std::size_t>(state.settings.transfer)];
  ImGui::TextWrapped("BRDF: %s", brdf::to_spec(brdf).c_str());
  int diffuse = state.diffuse_lobes_only ? 1 : 0;
  ImGui::RadioButton("glossy", &diffuse, 0);
  ImGui::SameLine();
  ImGui::RadioButton("diffuse only (G)", &diffuse, 1);
  if ((diffuse == 1) != state.diffuse_lobes_only) {
    state.diffuse_lobes_only = diffuse == 1;
    state.brdf_changed = true;
  }
  for (std::size_t i = 0; i < brdf.lobes.size(); ++i) {
    brdf::Lobe& lobe = brdf.lobes[i];
    ImGui::PushID(static_cast<int>(i));
    bool changed = false;
    switch (lobe.type) {
      case brdf::LobeType::lambert: changed = edit_colour("lambert albedo", lobe.weight); break;
      case brdf::LobeType::phong:
      case brdf::LobeType::blinn_phong: {
        float exponent = static_cast<float>(lobe.exponent);
        if (ImGui::SliderFloat(lobe.type == brdf::LobeType::phong ? "phong exponent" : "blinn exponent", &exponent, 0.0f, 10000.0f,
                               "%.1f", ImGuiSliderFlags_Logarithmic)) {
          lobe.exponent = std::clamp(static_cast<double>(exponent), 0.0, 100000.0);
          changed = true;
        }
        changed = edit_colour("ks", lobe.weight) || changed;
        break;
      }
      case brdf::LobeType::ggx: {
        float roughness = static_cast<float>(lobe.roughness);
        if (ImGui::SliderFloat("ggx roughness", &roughness, 0.01f, 1.0f, "%.3f")) {
          lobe.roughness = std::clamp(static_cast<double>(roughness), 0.01, 1.0);
          changed = true;
        }
        changed = edit_colour("F0", lobe.weight) || changed;
        break;
      }
    }
    ImGui::PopID();
    if (changed) state.brdf_changed = true;
  }
  ImGui::TextDisabled("B re-projected on the CPU in %.1f ms", state.projection_ms);
}

void cycle_background(ViewerState& state) {
  Background& b = state.settings.background;
  b = b == Background::environment ? Background::sh : b == Background::sh ? Background::black : Background::environment;
}

}  // namespace

brdf::Brdf shown_brdf(const ViewerState& state) {
  const brdf::Brdf& full = state.transfer_brdfs[static_cast<std::size_t>(state.settings.transfer)];
  if (!state.diffuse_lobes_only) return full;
  brdf::Brdf diffuse;
  for (const brdf::Lobe& lobe : full.lobes)
    if (lobe.type == brdf::LobeType::lambert) diffuse.lobes.push_back(lobe);
  if (diffuse.lobes.empty()) diffuse.lobes.push_back(brdf::Lobe{brdf::LobeType::lambert, glm::dvec3(0.8), 0.0, 0.0});
  return diffuse;
}

void sanitise(ViewerState& state) {
  FrameSettings& s = state.settings;
  s.transfer = std::clamp(s.transfer, 0, static_cast<int>(state.transfer_bands.size()) - 1);
  s.bands = std::clamp(s.bands, 0, state.current_bands());
  s.camera.elevation_degrees = std::clamp(s.camera.elevation_degrees, -kMaxElevation, kMaxElevation);
  if (!(s.camera.distance > 1e-9)) s.camera.distance = 1e-9;
  state.environment = std::clamp(state.environment, 0, static_cast<int>(state.environments.size()) - 1);
  const bool has_image = state.environments[static_cast<std::size_t>(state.environment)].has_image;
  if (s.background == Background::environment && !has_image) s.background = Background::sh;
  state.exposure = std::clamp(state.exposure, -20.0, 20.0);
}

bool apply_key(ViewerState& state, int key, int mods) {
  FrameSettings& s = state.settings;
  const int bands = s.bands == 0 ? state.current_bands() : s.bands;
  const int environment_count = static_cast<int>(state.environments.size());
  switch (key) {
    case GLFW_KEY_ESCAPE:
    case GLFW_KEY_Q: return true;
    case GLFW_KEY_H: state.show_panel = !state.show_panel; break;
    case GLFW_KEY_LEFT_BRACKET: s.bands = std::max(1, bands - 1); break;
    case GLFW_KEY_RIGHT_BRACKET: s.bands = std::min(state.current_bands(), bands + 1); break;
    case GLFW_KEY_MINUS:
    case GLFW_KEY_KP_SUBTRACT: state.exposure -= kExposureStep; break;
    case GLFW_KEY_EQUAL:
    case GLFW_KEY_KP_ADD: state.exposure += kExposureStep; break;
    case GLFW_KEY_E:
      state.environment = (state.environment + ((mods & GLFW_MOD_SHIFT) ? environment_count - 1 : 1)) % environment_count;
      state.environment_changed = true;
      break;
    case GLFW_KEY_B:
      cycle_background(state);
      if (s.background == Background::environment &&
          !state.environments[static_cast<std::size_t>(state.environment)].has_image)
        cycle_background(state);
      break;
    case GLFW_KEY_L: s.shading = s.shading == Shading::prt ? Shading::lambert : Shading::prt; break;
    case GLFW_KEY_U: s.sun = !s.sun; break;
    case GLFW_KEY_G:
      if (state.current_glossy() && !state.current_table()) {
        state.diffuse_lobes_only = !state.diffuse_lobes_only;
        state.brdf_changed = true;
      }
      break;
    case GLFW_KEY_T:
      state.tone_map = state.tone_map == image::ToneMap::aces ? image::ToneMap::clamp : image::ToneMap::aces;
      break;
    case GLFW_KEY_R: state.reset_requested = true; break;
    case GLFW_KEY_S: state.screenshot_requested = true; break;
    default:
      if (key >= GLFW_KEY_1 && key <= GLFW_KEY_9 && key - GLFW_KEY_1 < static_cast<int>(state.transfer_bands.size())) {
        s.transfer = key - GLFW_KEY_1;
        s.bands = 0;
        state.brdf_changed = true;  // the G toggle applies to the newly chosen glossy transfer too
      }
      break;
  }
  sanitise(state);
  return false;
}

namespace {

// Frame and GPU times, the renderer, the mesh size.
void draw_status(ViewerState& state) {
  ImGui::Text("frame %.2f ms (%.0f fps)", state.frame_ms, state.frame_ms > 0.0 ? 1000.0 / state.frame_ms : 0.0);
  ImGui::Text("GPU render %.2f ms", state.render_ms);
  ImGui::TextWrapped("%s", state.renderer_name.c_str());
  ImGui::Text("%zu vertices, %zu triangles", state.vertex_count, state.triangle_count);
}

// PRT or Lambert, the transfer, its band count and (glossy) BRDF.
void draw_shading_controls(ViewerState& state) {
  FrameSettings& s = state.settings;
  int shading = s.shading == Shading::prt ? 0 : 1;
  ImGui::RadioButton("PRT", &shading, 0);
  ImGui::SameLine();
  ImGui::RadioButton("Lambert (L)", &shading, 1);
  s.shading = shading == 0 ? Shading::prt : Shading::lambert;
  if (state.transfer_names.size() > 1) {
    const char* current = state.transfer_names[static_cast<std::size_t>(s.transfer)].c_str();
    if (ImGui::BeginCombo("transfer 1-9", current)) {
      for (std::size_t i = 0; i < state.transfer_names.size(); ++i) {
        if (ImGui::Selectable(state.transfer_names[i].c_str(), static_cast<int>(i) == s.transfer)) {
          s.transfer = static_cast<int>(i);
          s.bands = 0;
          state.brdf_changed = true;
        }
      }
      ImGui::EndCombo();
    }
  } else {
    ImGui::TextWrapped("transfer: %s", state.transfer_names[0].c_str());
  }
  int bands = s.bands == 0 ? state.current_bands() : s.bands;
  if (ImGui::SliderInt("bands [ ]", &bands, 1, state.current_bands())) s.bands = bands;
  if (state.current_glossy()) draw_brdf_controls(state);
}

// Exposure and tone map.
void draw_exposure_controls(ViewerState& state) {
  float exposure = static_cast<float>(state.exposure);
  if (ImGui::SliderFloat("exposure - =", &exposure, -10.0f, 10.0f, "%.1f")) state.exposure = exposure;
  int tone_map = state.tone_map == image::ToneMap::aces ? 0 : 1;
  ImGui::RadioButton("ACES", &tone_map, 0);
  ImGui::SameLine();
  ImGui::RadioButton("clamp (T)", &tone_map, 1);
  state.tone_map = tone_map == 0 ? image::ToneMap::aces : image::ToneMap::clamp;
}

// The environment, the light and object rotations, the sun, the background.
void draw_lighting_controls(ViewerState& state) {
  FrameSettings& s = state.settings;
  const char* environment_name = state.environments[static_cast<std::size_t>(state.environment)].source.c_str();
  if (ImGui::BeginCombo("environment E", environment_name)) {
    for (std::size_t i = 0; i < state.environments.size(); ++i) {
      const std::string name = std::filesystem::path(state.environments[i].source).filename().string();
      if (ImGui::Selectable((name + "##" + std::to_string(i)).c_str(), static_cast<int>(i) == state.environment)) {
        state.environment = static_cast<int>(i);
        state.environment_changed = true;
      }
    }
    ImGui::EndCombo();
  }
  ImGui::TextDisabled("drop an image or .json to add one");
  slider_angles("light y p r", state.light_angles);
  ImGui::TextDisabled("Shift/right drag turns the light");
  slider_angles("object y p r", state.object_angles);
  ImGui::TextDisabled("Ctrl/middle drag turns the object");
  draw_sun_controls(state);
  int background = static_cast<int>(s.background);
  const bool has_image = state.environments[static_cast<std::size_t>(state.environment)].has_image;
  ImGui::Text("background (B):");
  ImGui::SameLine();
  if (!has_image) ImGui::BeginDisabled();
  ImGui::RadioButton("env", &background, static_cast<int>(Background::environment));
  if (!has_image) ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::RadioButton("SH", &background, static_cast<int>(Background::sh));
  ImGui::SameLine();
  ImGui::RadioButton("black", &background, static_cast<int>(Background::black));
  s.background = static_cast<Background>(background);
}

// Orbit angles and distance, screenshot and reset.
void draw_camera_controls(ViewerState& state) {
  FrameSettings& s = state.settings;
  float camera[2] = {static_cast<float>(s.camera.azimuth_degrees), static_cast<float>(s.camera.elevation_degrees)};
  if (ImGui::SliderFloat2("azim. elev.", camera, -180.0f, 180.0f, "%.1f")) {
    s.camera.azimuth_degrees = camera[0];
    s.camera.elevation_degrees = camera[1];
  }
  float distance = static_cast<float>(s.camera.distance);
  if (ImGui::InputFloat("distance", &distance, 0.0f, 0.0f, "%.3f")) s.camera.distance = distance;
  if (ImGui::Button("screenshot (S)")) state.screenshot_requested = true;
  ImGui::SameLine();
  if (ImGui::Button("reset view (R)")) state.reset_requested = true;
}

}  // namespace

void draw_panel(ViewerState& state) {
  ImGui::SetNextWindowPos(ImVec2(6, 6), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(kPanelWidth, 0), ImGuiCond_FirstUseEver);
  ImGui::Begin("prt view (H hides)");
  // Widgets leave room for the longest label, so no label is cut off.
  ImGui::PushItemWidth(-(ImGui::CalcTextSize(kLongestLabel).x + ImGui::GetStyle().ItemInnerSpacing.x));
  draw_status(state);
  ImGui::Separator();
  draw_shading_controls(state);
  draw_exposure_controls(state);
  ImGui::Separator();
  draw_lighting_controls(state);
  ImGui::Separator();
  draw_camera_controls(state);
  if (!state.message.empty()) ImGui::TextWrapped("%s", state.message.c_str());
  ImGui::PopItemWidth();
  ImGui::End();
  sanitise(state);
}

}  // namespace prt::render::viewer_detail
