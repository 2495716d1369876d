#pragma once
// Internal to the renderer: the sun, shared frame state of every pass (renderer.h, PASSES: sun). The
// discs (light/disc.h) and their SH, one shadow map per disc, and the lookups the SUN variants of the
// passes make (shaders/sun_light.glsl); the deferred per-pixel direct light of diffuse passes. What the
// discs do to one transfer (its shadows flag, albedo, BRDF terms, bounce light) is that pass's own
// SunSurface; how a pass shades the discs is up to the pass (transfer_pass.h).
#include <array>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "brdf/brdf.h"
#include "light/disc.h"
#include "render/renderer.h"
#include "render/shader_program.h"

namespace prt::render {

struct FrameCore;
class BaseColour;

/// Most BRDF terms (brdf::terms) the discs' glossy direct light evaluates (sun_light.glsl: max_terms).
inline constexpr int kMaxBrdfTerms = 8;

/// What the discs need of one transfer's surface.
struct SunSurface {
  SunSurface() = default;
  ~SunSurface();
  SunSurface(const SunSurface&) = delete;
  SunSurface& operator=(const SunSurface&) = delete;

  /// The per-vertex albedo of the discs' diffuse direct light (Renderer::set_surface_albedo).
  void set_albedo(const std::vector<glm::vec3>& albedo);

  std::string origin;                               ///< the transfer's file, for warnings
  bool shadows = true;                              ///< false for unshadowed transfer
  GLuint albedo = 0;                                ///< x y z floats per vertex (0: the mesh's albedo)
  GLuint surface_buffer = 0, surface_texture = 0;   ///< deferred pass: position, normal, albedo per vertex
  std::vector<brdf::Term> terms;                    ///< glossy: the BRDF for the direct light
  /// Glossy with one BRDF per vertex (Renderer::set_brdfs): each BRDF's terms as sun_light.glsl's
  /// BrdfTerms reads them (2 kMaxBrdfTerms vec4 per BRDF), or 0; the pass binds the vertices' indices.
  GLuint term_table = 0;
  bool has_terms = false;
  bool warned = false;                              ///< the "no bounce-only section" warning was printed
};

class SunLight {
 public:
  SunLight();
  ~SunLight();
  SunLight(const SunLight&) = delete;
  SunLight& operator=(const SunLight&) = delete;

  /// See Renderer::set_discs.
  void set_discs(const std::vector<light::Disc>& discs);
  const std::vector<light::Disc>& discs() const { return discs_; }
  /// Their SH radiance, environment frame, kMaxBands^2.
  const std::vector<glm::vec3>& disc_lighting() const { return disc_lighting_; }
  /// Bumped by set_discs (what the shadow maps and every bounce light depend on).
  int version() const { return version_; }
  int updates() const { return updates_; }
  /// Drops the mesh's state (a new mesh).
  void clear_mesh();

  /// Redraws the shadow maps if the discs or `rotation` (R_object^T R_environment) changed.
  void update_maps(const FrameCore& core, const glm::dmat3& rotation);
  /// Binds the discs' uniforms, shadow maps and, for `glossy`, `surface`'s BRDF terms for `program`;
  /// otherwise the albedo buffer (binding 6) of `surface` (the mesh's if it has none).
  void bind(const FrameCore& core, const Program& program, const SunSurface& surface, bool glossy) const;
  /// The discs' uniforms of the background's DISCS variant.
  void bind_background(const Program& program) const;
  /// Depth-only draw of the mesh before a SUN draw (each pixel then runs the lookups once).
  void draw_prepass(const FrameCore& core) const;
  /// The discs' direct light over the pixels the diffuse mesh draw covered; with `base_colour` (not
  /// null: the draw was albedo-free, a textured mesh), the draw's radiance and the direct light both
  /// times the base colour at the pixel instead of the interpolated albedo.
  void draw_deferred(FrameCore& core, const FrameSettings& settings, SunSurface& surface,
                     const BaseColour* base_colour = nullptr);
  /// Visibility of disc `disc` at every vertex as the passes evaluate it (Renderer::shadow_visibility).
  std::vector<float> visibility(const FrameCore& core, int disc) const;

 private:
  void draw_maps(const FrameCore& core);
  void bind_surface(const FrameCore& core, SunSurface& surface);

  std::vector<light::Disc> discs_;                 // environment frame, at most kMaxDiscs
  std::vector<glm::vec3> disc_lighting_;
  int version_ = 0;
  int updates_ = 0;

  Program shadow_program_, visibility_program_, minmax_program_, deferred_program_;
  GLuint shadow_texture_ = 0, shadow_framebuffer_ = 0;
  GLuint triangle_buffer_ = 0, triangle_texture_ = 0;  // deferred pass: corner indices per triangle
  GLuint tile_texture_ = 0;                        // per tile of kShadowTile^2 texels: least, greatest depth

  bool maps_valid_ = false;
  glm::dmat3 maps_rotation_{1.0};
  int maps_version_ = -1;
  std::array<glm::mat4, kMaxDiscs> shadow_matrix_{};  // mesh coordinates -> (u, v, depth) in [0,1]
  std::array<glm::mat4, kMaxDiscs> light_projection_{};
  std::array<glm::vec3, kMaxDiscs> direction_{};       // object frame
  std::array<float, kMaxDiscs> depth_scale_{};  // mesh units per unit of stored depth
  std::array<float, kMaxDiscs> texel_{};        // mesh units per texel
};

}  // namespace prt::render
