#pragma once
// Internal to the renderer (renderer.cpp, renderer_glossy.cpp, renderer_sun.cpp): the sun pass's state
// (renderer.h, PASSES: sun).
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "brdf/brdf.h"
#include "light/disc.h"
#include "render/renderer.h"
#include "transfer/transfer_file.h"

namespace prt::render {

struct Renderer::SunPass {
  SunPass();
  ~SunPass();
  SunPass(const SunPass&) = delete;
  SunPass& operator=(const SunPass&) = delete;

  /// Drops the per-transfer state (a new mesh).
  void clear_mesh();
  /// Keeps what transfer `transfer` needs for the discs: its bounce-only part (CPU copy for diffuse,
  /// a TransferBuffer for glossy), and whether it casts shadows.
  void add_transfer(const transfer::TransferData& transfer, const std::string& origin, std::size_t max_range_bytes);

  struct PerTransfer {
    std::string origin;
    bool glossy = false, shadows = true, interreflected = false, warned = false;
    transfer::TransferData bounce_cpu;             ///< diffuse: the bounce-only part (values empty if none)
    std::unique_ptr<TransferBuffer> bounce_gpu;    ///< glossy: the bounce-only part (nullptr if none)
    GLuint albedo = 0;                             ///< x y z floats per vertex (0: the mesh's albedo)
    GLuint surface_buffer = 0, surface_texture = 0;  ///< deferred pass: position, normal, albedo per vertex
    std::vector<brdf::Term> terms;                 ///< glossy: the BRDF for the direct light
    bool has_terms = false;
  };
  std::vector<PerTransfer> transfers;

  std::vector<light::Disc> discs;                  ///< environment frame, at most kMaxDiscs
  std::vector<glm::vec3> disc_lighting;            ///< their SH radiance, environment frame, kMaxBands^2
  int disc_version = 0;                            ///< bumped by set_discs (the maps depend on the discs only)
  int version = 0;                                 ///< bumped by set_discs and BRDF changes (the bounce light)
  int updates = 0;                                 ///< shadow-map redraws

  Program shadow_program, visibility_program, minmax_program, deferred_program;
  GLuint shadow_texture = 0, shadow_framebuffer = 0;
  GLuint triangle_buffer = 0, triangle_texture = 0;  ///< deferred pass: corner indices per triangle
  GLuint tile_texture = 0;                         ///< per tile of kShadowTile^2 texels: least, greatest depth
  GLuint disc_lighting_buffer = 0;                 ///< object-frame disc SH (uniform Lighting layout)
  GLuint bounce_vertex = 0;                        ///< diffuse: x y z floats per vertex
  GLuint bounce_outgoing = 0;                      ///< glossy: vec4 per coefficient per vertex
  std::size_t bounce_outgoing_bytes = 0;

  // What the shadow maps and the bounce light were last computed for.
  bool maps_valid = false, bounce_valid = false;
  glm::dmat3 maps_rotation{1.0}, bounce_rotation{1.0};
  int maps_version = -1, bounce_version = -1, bounce_transfer = -1, bounce_bands = -1;

  // The maps' geometry (object frame).
  std::array<glm::mat4, kMaxDiscs> shadow_matrix{};  ///< mesh coordinates -> (u, v, depth) in [0,1]
  std::array<glm::mat4, kMaxDiscs> light_projection{};
  std::array<glm::vec3, kMaxDiscs> direction{};       ///< object frame
  std::array<float, kMaxDiscs> depth_scale{};  ///< mesh units per unit of stored depth
  std::array<float, kMaxDiscs> texel{};        ///< mesh units per texel
};

}  // namespace prt::render
