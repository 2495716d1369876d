#pragma once
// Internal to the renderer: the frame core, the state every pass shares (renderer.h, PASSES). The mesh
// on the GPU, the lighting (environment frame, and rotated into the object's frame each frame), the
// float framebuffer, the camera of the frame, the background, the Lambert baseline, the tone map and the
// sun (sun_light.h: discs and their shadow maps). A transfer pass (transfer_pass.h) reads and binds
// these; it owns only what belongs to its transfer.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "render/base_colour.h"
#include "render/renderer.h"
#include "render/shader_program.h"
#include "render/sun_light.h"
#include "render/triangle_runs.h"

namespace prt::render {

/// Uniform-buffer binding of the object-frame lighting (uniform Lighting of the PRT shaders).
inline constexpr GLuint kObjectLightingBinding = 0;
/// local_size_x of the renderer's per-vertex compute passes.
inline constexpr GLuint kWorkgroupSize = 64;

/// A GL buffer of `bytes` (at least 4) holding `data` (may be null), with storage flags `flags`.
GLuint make_buffer(GLsizeiptr bytes, const void* data, GLbitfield flags);

struct FrameCore {
  FrameCore();
  ~FrameCore();
  FrameCore(const FrameCore&) = delete;
  FrameCore& operator=(const FrameCore&) = delete;

  /// Uploads positions, normals, albedo (0.8 grey where the mesh has none), indices and lightmap UVs.
  void set_mesh(const mesh::Mesh& mesh);
  /// See Renderer::set_lighting.
  void set_lighting(const sh::RgbCoefficients& lighting, const image::Image* equirect);
  /// See Renderer::update_lighting: fills `rotated` and uploads it to object_lighting.
  void update_lighting(const glm::dmat3& environment_rotation, const glm::dmat3& object_rotation, int bands);
  /// Resizes the float framebuffer (no-op at the same size).
  void resize(int width, int height);
  /// The camera of a frame of width x height (view, model_view_projection).
  void set_view(const Camera& camera, const glm::dmat3& object_rotation, int width, int height);
  /// Binds the framebuffer with the frame's fixed state and clears it (depth too if `depth`).
  void begin_frame(bool depth);
  /// The background: the sky, its SH or nothing; with the discs drawn over it (settings.sun).
  void draw_background(const FrameSettings& settings, int bands);
  /// The Lambert baseline (Shading::lambert).
  void draw_lambert(const FrameSettings& settings);
  /// The program for `stages` with `defines`, compiled on first use and kept.
  const Program& program(const std::vector<std::string>& stages, const std::string& defines = "");
  /// The discs' SH in the object frame for `settings`' rotations, first `bands` bands.
  std::vector<glm::vec3> object_disc_lighting(const FrameSettings& settings, int bands) const;
  /// The eye of the frame in mesh coordinates: p = c + R_object^T (eye - c).
  glm::vec3 eye_object(const FrameSettings& settings) const;
  void draw_mesh_elements() const;  ///< glDrawElements of the whole mesh (mesh_vao bound by the caller)
  /// glDrawElements of the triangles `runs` (all when null) with `program` in use (draw_runs).
  void draw_mesh_elements(const Program& program, const TriangleRuns* runs) const;
  /// A deferred pass over the pixels the mesh draw covered (prt_sun.frag): writes to
  /// the radiance attachment only, with the depth test passing only where the mesh is; uses `program`,
  /// binds the frame's radiance (unit 11) and triangle index (unit 12) and sets pixel_surface.glsl's
  /// uniforms for `settings`. The caller then binds its own inputs and calls end_deferred, which draws
  /// and restores the frame's state.
  void begin_deferred(const Program& program, const FrameSettings& settings) const;
  void end_deferred() const;

  // The mesh.
  GLuint empty_vao = 0, mesh_vao = 0;
  GLuint positions = 0, normals = 0, albedo = 0, indices = 0;
  GLuint lightmap_uv = 0;                ///< the mesh's lightmap UVs, vec2 per triangle corner (0: none)
  std::size_t lightmap_uv_corners = 0;
  GLsizei index_count = 0;
  std::size_t vertex_count = 0;
  mesh::Bounds bounds;
  bool has_mesh = false;

  // The lighting.
  std::vector<glm::vec3> lighting;   ///< environment frame, padded to kMaxBands^2
  int lighting_bands = 1;
  std::vector<glm::vec3> rotated;    ///< this frame's lighting in the object's frame
  std::vector<glm::vec4> upload;     ///< scratch: std140 layout
  glm::dvec3 lambert_direction{0.0, 1.0, 0.0}, lambert_radiance{0.0};
  GLuint object_lighting = 0, environment_lighting = 0;  ///< uniform buffers, kMaxBands^2 vec4 each
  GLuint environment_texture = 0;

  // The frame.
  GLuint framebuffer = 0, radiance_texture = 0, triangle_texture = 0, depth_buffer = 0;
  int width = 0, height = 0;
  ViewMatrices view;
  glm::mat4 model_view_projection{1.0f};

  std::unique_ptr<SunLight> sun;
  BaseColour base_colour;  ///< a textured mesh's base colour (empty otherwise)
  Program tonemap;

 private:
  void draw_background_pass(const Program& program, const FrameSettings& settings, int bands);
  Program background_, background_discs_, lambert_;
  std::map<std::pair<std::string, std::string>, Program> programs_;
};

}  // namespace prt::render
