#pragma once
// Internal to the renderer: a textured mesh's base colour on the GPU, per pixel (renderer.h, PASSES:
// texture; docs/conventions.md "Albedo and textures", the albedo split). Every texture of the mesh in one
// float buffer (GL_RGB32F, linear as the loader decoded it, rows one texture after another) read through
// a buffer texture; the materials (factor, KHR_texture_transform as an affine map, the texture's place
// and size, its wrap modes and filter), the per-corner base-colour UVs, the per-triangle material and
// the vertex colours in storage buffers. shaders/base_colour.glsl filters by hand, as
// mesh::sample_texture does: one buffer takes any number of textures of any sizes, the per-pixel
// material index needs no uniform control flow (an array of samplers would), and the lookup is the
// conventions' exactly (float weights, texel centres, the three wrap modes, the nearest filter).
#include <cstddef>

#include "mesh/mesh.h"
#include "render/gl.h"
#include "render/shader_program.h"

namespace prt::render {

struct FrameCore;
struct FrameSettings;

class BaseColour {
 public:
  BaseColour() = default;
  ~BaseColour();
  BaseColour(const BaseColour&) = delete;
  BaseColour& operator=(const BaseColour&) = delete;

  /// Uploads the base colour of `mesh` if it is textured (mesh::Mesh::textured()), else drops the
  /// previous mesh's. Throws prt::Error if the textures together exceed GL_MAX_TEXTURE_BUFFER_SIZE texels.
  void set_mesh(const mesh::Mesh& mesh);
  /// The mesh has a texture (set_mesh uploaded its base colour).
  bool present() const { return texels_ != 0; }
  /// Binds the buffers base_colour.glsl reads (storage buffers 12-15, texture unit 15) and sets
  /// `program`'s has_vertex_colour (the program in use). The triangle indices (binding 3) are the caller's.
  void bind(const Program& program) const;
  /// Multiplies the radiance of every pixel the mesh draw covered by the base colour there (prt_texture.frag):
  /// after a draw of albedo-free radiance without discs. Precondition: present().
  void draw_deferred(FrameCore& core, const FrameSettings& settings) const;

 private:
  GLuint materials_ = 0, uv_ = 0, triangle_material_ = 0, vertex_colour_ = 0;
  GLuint texel_buffer_ = 0, texels_ = 0;  // the buffer and its GL_RGB32F buffer texture
  bool has_vertex_colour_ = false;
};

}  // namespace prt::render
