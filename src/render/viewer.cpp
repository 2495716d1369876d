#include "render/viewer.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "render/gl.h"  // before GLFW, which then includes no GL header of its own
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include "brdf/projection.h"
#include "core/error.h"
#include "shade/glossy.h"
#include "shade/surface_albedo.h"
#include "render/mixed_frame.h"
#include "render/renderer_cpca.h"
#include "render/viewer_state.h"
#include "sh/rotation.h"

namespace prt::render {

namespace {

using viewer_detail::ViewerState;

constexpr double kDragDegreesPerPixel = 0.25;
constexpr double kZoomPerNotch = 0.9;

std::string glfw_error() {
  const char* description = nullptr;
  glfwGetError(&description);
  return description != nullptr ? description : "unknown GLFW error";
}

// GLFW and the window, released in reverse order whatever happens.
class Window {
 public:
  Window(int width, int height, bool vsync) {
    if (glfwInit() != GLFW_TRUE)
      fail("cannot open a window: " + glfw_error() + " (prt view needs a display; use xvfb-run -a without one)");
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, kGlMajor);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, kGlMinor);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_SRGB_CAPABLE, GLFW_FALSE);
    window_ = glfwCreateWindow(width, height, "prt view", nullptr, nullptr);
    if (window_ == nullptr) {
      const std::string why = glfw_error();
      glfwTerminate();
      fail("cannot open a window with an OpenGL 4.5 core context: " + why);
    }
    glfwMakeContextCurrent(window_);
    glfwSwapInterval(vsync ? 1 : 0);
  }
  ~Window() {
    glfwDestroyWindow(window_);
    glfwTerminate();
  }
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;
  GLFWwindow* get() const { return window_; }

 private:
  GLFWwindow* window_ = nullptr;
};

// Dear ImGui's context and backends.
class Gui {
 public:
  explicit Gui(GLFWwindow* window) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini left in the user's folder
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForOpenGL(window, true);  // chains the callbacks installed before
    ImGui_ImplOpenGL3_Init("#version 450 core");
  }
  ~Gui() {
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
  }
  Gui(const Gui&) = delete;
  Gui& operator=(const Gui&) = delete;
};

// GL timer queries, read one frame late so the CPU does not wait for the GPU.
class FrameTimer {
 public:
  FrameTimer() { glGenQueries(2, queries_); }
  ~FrameTimer() { glDeleteQueries(2, queries_); }
  FrameTimer(const FrameTimer&) = delete;
  FrameTimer& operator=(const FrameTimer&) = delete;
  void begin() { glBeginQuery(GL_TIME_ELAPSED, queries_[frame_ % 2]); }
  // Ends this frame's query; returns the previous frame's GPU time in ms (0 for the first frame).
  double end() {
    glEndQuery(GL_TIME_ELAPSED);
    double ms = 0.0;
    if (frame_ > 0) {
      GLuint64 nanoseconds = 0;
      glGetQueryObjectui64v(queries_[(frame_ + 1) % 2], GL_QUERY_RESULT, &nanoseconds);
      ms = static_cast<double>(nanoseconds) * 1e-6;
    }
    ++frame_;
    return ms;
  }

 private:
  GLuint queries_[2] = {0, 0};
  unsigned long frame_ = 0;
};

// A mixed pair among the transfers: its texel file's index (the per-vertex file follows) and the
// triangles drawn per vertex.
struct MixedEntry {
  std::size_t texel = 0;
  TriangleRuns vertex_runs;
};

enum class Drag { none, camera, light, object };

// What the GLFW callbacks reach through the window's user pointer.
struct Session {
  ViewerState state;
  Drag drag = Drag::none;
  double last_x = 0.0, last_y = 0.0;
  bool quit = false;
};

Session* session_of(GLFWwindow* window) { return static_cast<Session*>(glfwGetWindowUserPointer(window)); }

double wrap_degrees(double angle) { return std::remainder(angle, 360.0); }

void on_mouse_button(GLFWwindow* window, int button, int action, int mods) {
  if (session_of(window) == nullptr) return;
  Session& s = *session_of(window);
  if (action == GLFW_RELEASE) {
    s.drag = Drag::none;
    return;
  }
  if (ImGui::GetIO().WantCaptureMouse) return;
  glfwGetCursorPos(window, &s.last_x, &s.last_y);
  if (button == GLFW_MOUSE_BUTTON_LEFT) {
    s.drag = (mods & GLFW_MOD_SHIFT) ? Drag::light : (mods & GLFW_MOD_CONTROL) ? Drag::object : Drag::camera;
  } else if (button == GLFW_MOUSE_BUTTON_RIGHT) {
    s.drag = Drag::light;
  } else if (button == GLFW_MOUSE_BUTTON_MIDDLE) {
    s.drag = Drag::object;
  }
}

void on_cursor(GLFWwindow* window, double x, double y) {
  if (session_of(window) == nullptr) return;
  Session& s = *session_of(window);
  if (s.drag == Drag::none) return;
  const double dx = (x - s.last_x) * kDragDegreesPerPixel, dy = (y - s.last_y) * kDragDegreesPerPixel;
  s.last_x = x;
  s.last_y = y;
  ViewerState& state = s.state;
  if (s.drag == Drag::camera) {
    // The object follows the mouse: dragging right turns the camera the other way.
    state.settings.camera.azimuth_degrees = wrap_degrees(state.settings.camera.azimuth_degrees - dx);
    state.settings.camera.elevation_degrees += dy;
  } else {
    glm::dvec3& angles = s.drag == Drag::light ? state.light_angles : state.object_angles;
    angles.x = wrap_degrees(angles.x + dx);
    angles.y = wrap_degrees(angles.y + dy);
  }
  viewer_detail::sanitise(state);
}

void on_scroll(GLFWwindow* window, double, double y_offset) {
  if (session_of(window) == nullptr || ImGui::GetIO().WantCaptureMouse) return;
  Session& s = *session_of(window);
  s.state.settings.camera.distance *= std::pow(kZoomPerNotch, y_offset);
}

void on_key(GLFWwindow* window, int key, int, int action, int mods) {
  if (session_of(window) == nullptr || action == GLFW_RELEASE || ImGui::GetIO().WantCaptureKeyboard) return;
  Session& s = *session_of(window);
  if (viewer_detail::apply_key(s.state, key, mods)) s.quit = true;
}

void on_drop(GLFWwindow* window, int count, const char** paths) {
  if (session_of(window) == nullptr) return;
  Session& s = *session_of(window);
  for (int i = 0; i < count; ++i) s.state.dropped.emplace_back(paths[i]);
}

void save_image(const Renderer& renderer, const ViewerState& state, const std::string& path) {
  const image::Image radiance = renderer.read_radiance();
  if (image::is_display_format(path)) {
    image::write(path, image::to_display(radiance, state.exposure, state.tone_map));
  } else {
    image::write(path, radiance);
  }
}

std::string free_screenshot_stem() {
  for (int n = 1;; ++n) {
    char stem[32];
    std::snprintf(stem, sizeof stem, "prt-view-%03d", n);
    std::error_code error;
    if (!std::filesystem::exists(std::string(stem) + ".png", error) &&
        !std::filesystem::exists(std::string(stem) + ".exr", error))
      return stem;
  }
}

// Applies requests collected since the last frame (drops, environment switches, resets, screenshots
// are handled after drawing).
void apply_requests(Session& s, Renderer& renderer, const Camera& initial_camera, const ViewerOptions& options) {
  ViewerState& state = s.state;
  for (const std::string& path : state.dropped) {
    try {
      state.environments.push_back(load_render_lighting(path, state.projection_bands, state.sun_request, state.window_request));
      state.environment = static_cast<int>(state.environments.size()) - 1;
      state.environment_changed = true;
      state.message = "loaded " + path;
    } catch (const Error& e) {
      state.message = e.what();
      std::fprintf(stderr, "prt view: %s\n", e.what());
    }
  }
  state.dropped.clear();
  if (state.reset_requested) {
    state.settings.camera = initial_camera;
    state.light_angles = options.rotate;
    state.object_angles = options.object_rotate;
    state.reset_requested = false;
  }
  if (state.brdf_changed) {
    state.brdf_changed = false;
    if (state.current_glossy() && !state.current_table()) {
      // Live BRDF edits: re-project B on the CPU (tens of ms at 5 bands) and upload it.
      const auto start = std::chrono::steady_clock::now();
      try {
        const brdf::Brdf shown = viewer_detail::shown_brdf(state);
        renderer.set_brdf(state.settings.transfer,
                          brdf::project(shown, state.transfer_bands_out[static_cast<std::size_t>(state.settings.transfer)]), shown);
      } catch (const Error& e) {
        state.message = e.what();
      }
      state.projection_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    }
  }
  if (state.environment_changed) {
    const Lighting& lighting = state.environments[static_cast<std::size_t>(state.environment)];
    renderer.set_lighting(lighting.coefficients, lighting.has_image ? &lighting.equirect : nullptr);
    renderer.set_discs(lighting.discs);
    state.environment_changed = false;
  }
  viewer_detail::sanitise(state);
  state.settings.environment_rotation =
      sh::rotation_from_yaw_pitch_roll(state.light_angles.x, state.light_angles.y, state.light_angles.z);
  state.settings.object_rotation =
      sh::rotation_from_yaw_pitch_roll(state.object_angles.x, state.object_angles.y, state.object_angles.z);
}

// Refuses a --screenshot the scripted run cannot honour, before anything is loaded.
void check_screenshot_option(const ViewerOptions& options) {
  if (options.screenshot.empty()) return;
  if (options.frames <= 0) fail_option("screenshot", " needs a frame count (the frame to save)");
  if (!image::is_display_format(options.screenshot) && std::filesystem::path(options.screenshot).extension() != ".exr")
    fail_file(options.screenshot, "screenshot must be .png (tone mapped) or .exr (linear radiance)");
}

// Fills the viewer state from the loaded scene and the options: lighting, the transfers' labels,
// bands and BRDFs, and the initial view settings.
void init_state(ViewerState& state, const SceneInputs& scene, const ViewerOptions& options) {
  state.projection_bands = max_bands(scene);
  state.sun_request = options.sun;
  state.window_request = options.window;
  // The auto window's glossy criterion (light/deringing.h) when any transfer is glossy, as prt render.
  for (const auto& t : scene.transfers) state.window_request.radiance |= transfer::is_glossy(t.header.kind);
  for (const std::string& spec : options.environments)
    state.environments.push_back(load_render_lighting(spec, state.projection_bands, options.sun, state.window_request));
  for (std::size_t i = 0; i < scene.transfers.size(); ++i) {
    const transfer::Header& h = scene.transfers[i].header;
    state.transfer_names.push_back(std::filesystem::path(scene.transfer_paths[i]).filename().string() + " (" +
                                   transfer::kind_name(h.kind) + ", " + std::to_string(h.bands) + " bands, " +
                                   std::to_string(h.channels) + (h.channels == 1 ? " channel" : " channels") +
                                   transfer_memory_label(scene, i) + ")");
    state.transfer_bands.push_back(static_cast<int>(h.bands));
    const bool glossy = transfer::is_glossy(h.kind);
    const brdf::VertexBrdfs brdfs = glossy ? glossy_brdfs(scene.transfers[i], scene.transfer_paths[i], options.brdf)
                                           : brdf::VertexBrdfs{{brdf::Brdf{}}, {}};
    state.transfer_brdfs.push_back(brdfs.table[0]);
    state.transfer_tables.push_back(brdfs.table.size() > 1 ? brdfs : brdf::VertexBrdfs{});
    state.transfer_bands_out.push_back(glossy ? static_cast<int>(h.bands_out) : 0);
  }
  state.vertex_count = scene.mesh.vertex_count();
  state.triangle_count = scene.mesh.triangle_count();
  state.settings.bands = options.bands;
  state.settings.background = options.background.value_or(
      state.environments[0].has_image ? Background::environment : Background::sh);
  state.exposure = options.exposure;
  state.tone_map = options.tone_map;
  state.light_angles = options.rotate;
  state.object_angles = options.object_rotate;
  if (options.bands < 0 || options.bands > state.current_bands())
    fail_option("bands", ": must be between 1 and the transfer's " + std::to_string(state.current_bands()) + " bands");
}

// The transfer files of `options` with each mixed pair's partner (mixed_frame.h), and where each pair's
// texel file is in that list.
std::vector<std::string> expand_mixed_pairs(const ViewerOptions& options, std::vector<std::size_t>& pairs) {
  std::vector<std::string> paths;
  for (const std::string& path : options.transfer_paths) {
    const std::vector<std::string> expanded = mixed_transfer_paths(path);
    if (expanded.size() == 2) pairs.push_back(paths.size());
    paths.insert(paths.end(), expanded.begin(), expanded.end());
  }
  return paths;
}

// A mixed pair's entry after the files' own: "a.prt + a.vertices.prt (mixed, 5 bands, 14 of 16
// triangles per texel)", drawn in one frame (Renderer::add_mixed). The viewer starts on it when the
// first file given is of a pair.
void add_mixed_entries(ViewerState& state, const SceneInputs& scene, const std::vector<MixedEntry>& mixed) {
  for (std::size_t k = 0; k < mixed.size(); ++k) {
    const std::size_t t = mixed[k].texel;
    const transfer::Header& h = scene.transfers[t].header;
    std::uint64_t per_vertex = 0;
    for (const auto& run : mixed[k].vertex_runs) per_vertex += run.second;
    const auto name = [&](std::size_t i) { return std::filesystem::path(scene.transfer_paths[i]).filename().string(); };
    state.transfer_names.push_back(name(t) + " + " + name(t + 1) + " (mixed, " + std::to_string(h.bands) + " bands, " +
                                   std::to_string(scene.mesh.triangle_count() - per_vertex) + " of " +
                                   std::to_string(scene.mesh.triangle_count()) + " triangles per texel)");
    state.transfer_bands.push_back(static_cast<int>(h.bands));
    state.transfer_brdfs.emplace_back();
    state.transfer_tables.emplace_back();
    state.transfer_bands_out.push_back(0);
    if (k == 0 && t == 0) state.settings.transfer = static_cast<int>(scene.transfers.size());
  }
}

// Uploads the mesh and every transfer (with its BRDF or surface albedo) to the renderer, then each mixed
// pair's one-frame entry (add_mixed_entries).
void upload_scene(Renderer& renderer, const SceneInputs& scene, const ViewerState& state, const std::vector<MixedEntry>& mixed) {
  renderer.set_mesh(scene.mesh);
  for (std::size_t i = 0; i < scene.transfers.size(); ++i) {
    const int index = add_scene_transfer(renderer, scene, i);
    if (!state.transfer_tables[i].table.empty())
      renderer.set_brdfs(index, state.transfer_tables[i]);
    else if (!state.transfer_brdfs[i].empty())
      renderer.set_brdf(index, brdf::project(state.transfer_brdfs[i], state.transfer_bands_out[i]), state.transfer_brdfs[i]);
    else
      renderer.set_surface_albedo(index, shade::surface_albedo(scene.mesh, scene.transfers[i].header, scene.transfer_paths[i]));
  }
  for (const MixedEntry& entry : mixed)
    renderer.add_mixed(static_cast<int>(entry.texel), static_cast<int>(entry.texel + 1), entry.vertex_runs);
}

void install_callbacks(GLFWwindow* window, Session& session) {
  glfwSetWindowUserPointer(window, &session);
  glfwSetMouseButtonCallback(window, on_mouse_button);
  glfwSetCursorPosCallback(window, on_cursor);
  glfwSetScrollCallback(window, on_scroll);
  glfwSetKeyCallback(window, on_key);
  glfwSetDropCallback(window, on_drop);
}

// Saves a screenshot pair (PNG + EXR) under the next free prt-view-NNN name.
void save_screenshot(const Renderer& renderer, ViewerState& state) {
  const std::string stem = free_screenshot_stem();
  save_image(renderer, state, stem + ".png");
  save_image(renderer, state, stem + ".exr");
  state.message = "saved " + stem + ".png and " + stem + ".exr";
  std::fprintf(stderr, "prt view: %s\n", state.message.c_str());
}

// The frame loop: events, panel, render, present, until the window closes, the user quits or the
// scripted frame count is reached.
void run_frames(GLFWwindow* window, Session& session, Renderer& renderer, const Camera& initial_camera,
                const ViewerOptions& options) {
  ViewerState& state = session.state;
  const bool scripted = options.frames > 0;
  FrameTimer timer;
  int frames_drawn = 0, width = 0, height = 0;
  auto last = std::chrono::steady_clock::now();
  while (!glfwWindowShouldClose(window) && !session.quit) {
    glfwPollEvents();
    glfwGetFramebufferSize(window, &width, &height);
    if (width <= 0 || height <= 0) {  // minimised
      glfwWaitEvents();
      continue;
    }
    apply_requests(session, renderer, initial_camera, options);

    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    if (state.show_panel) viewer_detail::draw_panel(state);
    ImGui::Render();
    apply_requests(session, renderer, initial_camera, options);  // the panel's edits, this frame

    timer.begin();
    renderer.render(state.settings, width, height);
    const double gpu_ms = timer.end();
    if (gpu_ms > 0.0) state.render_ms = gpu_ms;
    renderer.present(0, state.exposure, state.tone_map);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());

    if (state.screenshot_requested) {
      state.screenshot_requested = false;
      save_screenshot(renderer, state);
    }
    ++frames_drawn;
    if (scripted && frames_drawn >= options.frames) {
      if (!options.screenshot.empty()) save_image(renderer, state, options.screenshot);
      break;
    }
    glfwSwapBuffers(window);

    const auto now = std::chrono::steady_clock::now();
    const double ms = std::chrono::duration<double, std::milli>(now - last).count();
    last = now;
    state.frame_ms = state.frame_ms == 0.0 ? ms : 0.9 * state.frame_ms + 0.1 * ms;
  }
}

}  // namespace

void run_viewer(const ViewerOptions& options) {
  check_screenshot_option(options);
  std::vector<std::size_t> pairs;
  SceneInputs scene = load_scene(options.mesh_path, expand_mixed_pairs(options, pairs), options.scene);
  std::vector<MixedEntry> mixed;
  for (std::size_t t : pairs) mixed.push_back({t, mixed_vertex_runs(scene, t)});
  Session session;
  ViewerState& state = session.state;
  init_state(state, scene, options);
  add_mixed_entries(state, scene, mixed);

  Window window(options.width, options.height, options.frames <= 0);
  install_callbacks(window.get(), session);
  Renderer renderer;
  upload_scene(renderer, scene, state, mixed);
  const mesh::Bounds bounds = mesh::bounds(scene.mesh);
  scene = SceneInputs();  // the GPU holds what is needed now
  state.renderer_name = describe_current_context();

  int width = 0, height = 0;
  glfwGetFramebufferSize(window.get(), &width, &height);
  Camera initial_camera = options.camera;
  initial_camera.distance = orbit_view(options.camera, bounds, std::max(width, 1), std::max(height, 1)).distance;
  state.settings.camera = initial_camera;

  Gui gui(window.get());
  run_frames(window.get(), session, renderer, initial_camera, options);
  glfwSetWindowUserPointer(window.get(), nullptr);
  glFinish();
}

}  // namespace prt::render
