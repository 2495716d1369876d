#pragma once
// Internal to the renderer: a textured mesh's base colour on the GPU, per pixel (renderer.h, PASSES:
// texture; docs/conventions.md "Albedo and textures", the albedo split). Each image is one GL_RGB32F
// texture (linear, as the loader decoded it: exact); each distinct (image, wrap s, wrap t, filter) of the
// materials is a texture slot, the image on texture unit 16 + slot with a sampler object of the glTF
// sampler's wrap modes and filter (bilinear, or nearest; no mipmaps). The materials (factor,
// KHR_texture_transform as an affine map, slot), the per-corner base-colour UVs, the per-triangle
// material and the vertex colours are storage buffers (shaders/base_material.glsl). A textured draw is
// one indexed draw over the mesh's draw vertices (textured_corners.h: one per distinct vertex, UV and
// material), each with the first corner it stands for as attribute 2, so UVs follow the corners across
// seams, the rasteriser interpolates them, and the vertex stage runs about once per mesh vertex, as the
// untextured draw's; the fragment stage picks its slot from a loop over the slots
// (shaders/base_texture.glsl: a sampler array may only be indexed uniformly).
#include <cstddef>
#include <string>
#include <vector>

#include "mesh/mesh.h"
#include "render/gl.h"
#include "render/shader_program.h"
#include "render/triangle_runs.h"

namespace prt::render {

struct FrameCore;

/// Most texture slots of one mesh (texture units 16 .. 16 + kMaxTextureSlots - 1).
inline constexpr int kMaxTextureSlots = 16;

class BaseColour {
 public:
  BaseColour() = default;
  ~BaseColour();
  BaseColour(const BaseColour&) = delete;
  BaseColour& operator=(const BaseColour&) = delete;

  /// Uploads the base colour of `mesh` if it is textured (mesh::Mesh::textured()), else drops the
  /// previous mesh's. Throws prt::Error if its materials need more than kMaxTextureSlots slots.
  void set_mesh(const mesh::Mesh& mesh);
  /// The mesh has a texture (set_mesh uploaded its base colour).
  bool present() const { return !textures_.empty(); }
  /// "#define TEXTURED 1" and "#define TEXTURE_SLOTS n" for the textured variants of the shaders.
  std::string defines() const;
  /// Binds what base_material.glsl and base_texture.glsl read (storage buffers 12-15, texture units and
  /// samplers 16 + slot) and sets `program`'s has_vertex_colour (the program in use). The triangle
  /// indices (binding 3) are the caller's.
  void bind(const Program& program) const;
  /// A textured per-vertex draw with `program` (in use): binds the above and the mesh's indices (3),
  /// positions (4) and albedo (11), and draws the triangles indexed over the draw vertices, whose
  /// attribute 2 is the corner 3 t + k each stands for (textured_vertex.glsl); the triangles of `runs`
  /// only (all when null: draw_runs, frame_core.h, so first_triangle + gl_PrimitiveID is the mesh's
  /// triangle index).
  void draw_corners(const FrameCore& core, const Program& program, const TriangleRuns* runs = nullptr) const;

 private:
  GLuint materials_ = 0, uv_ = 0, triangle_material_ = 0, vertex_colour_ = 0;
  GLuint corner_vao_ = 0, first_corner_ = 0, draw_indices_ = 0;  // the indexed draw (textured_corners.h)
  GLsizei corner_count_ = 0;
  std::vector<GLuint> textures_;  // per image
  std::vector<GLuint> samplers_;  // per slot
  std::vector<int> slot_image_;   // per slot: its image
  bool has_vertex_colour_ = false;
  void release();
  void upload_corners(const mesh::Mesh& mesh);
};

}  // namespace prt::render
