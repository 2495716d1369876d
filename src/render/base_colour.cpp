// A textured mesh's base colour on the GPU (base_colour.h).
#include "render/base_colour.h"

#include <tuple>
#include <vector>

#include <glm/vec4.hpp>

#include "core/error.h"
#include "mesh/texture.h"
#include "render/bindings.h"
#include "render/frame_core.h"
#include "render/textured_corners.h"

namespace prt::render {

namespace {

constexpr GLuint kMaterialsBinding = 12, kBaseUvBinding = 13, kTriangleMaterialBinding = 14, kVertexColourBinding = 15;
constexpr GLuint kAlbedoBinding = 11;  // textured_vertex.glsl: VertexAlbedo
constexpr GLuint kFirstSlotUnit = 16;
constexpr GLuint kCornerLocation = 2;  // textured_vertex.glsl: in uint draw_corner

// std430 layout of base_material.glsl's Material.
struct GpuMaterial {
  glm::vec4 factor;
  glm::vec4 transform_u, transform_v;  // u' = dot(transform_u.xyz, (u, v, 1)), v' likewise
  glm::ivec4 slot;                     // x: texture slot, -1 for none
};

// The affine map of a KHR_texture_transform, from mesh::transform_uv at three points.
void affine_transform(const mesh::TextureTransform& transform, GpuMaterial& m) {
  const glm::vec2 o = mesh::transform_uv(transform, glm::vec2(0.0f));
  const glm::vec2 du = mesh::transform_uv(transform, glm::vec2(1.0f, 0.0f)) - o;
  const glm::vec2 dv = mesh::transform_uv(transform, glm::vec2(0.0f, 1.0f)) - o;
  m.transform_u = glm::vec4(du.x, dv.x, o.x, 0.0f);
  m.transform_v = glm::vec4(du.y, dv.y, o.y, 0.0f);
}

GLint gl_wrap(mesh::Wrap wrap) {
  switch (wrap) {
    case mesh::Wrap::clamp_to_edge: return GL_CLAMP_TO_EDGE;
    case mesh::Wrap::mirrored_repeat: return GL_MIRRORED_REPEAT;
    case mesh::Wrap::repeat: break;
  }
  return GL_REPEAT;
}

GLuint rgb_texture(const mesh::Texture& texture) {
  GLuint id = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &id);
  glTextureStorage2D(id, 1, GL_RGBA32F, texture.width, texture.height);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  // Row 0 (the image's top, v = 0) goes to texture row t = 0: the shaders sample at t = v.
  // Linear floats from either form of the texture (8-bit codes through their decode table): exact.
  const std::vector<float> rgb = mesh::texture_rgb(texture);
  std::vector<float> rgba(rgb.size() / 3 * 4, 1.0f);
  for (std::size_t i = 0; i < rgb.size() / 3; ++i)
    for (int c = 0; c < 3; ++c) rgba[4 * i + c] = rgb[3 * i + c];
  glTextureSubImage2D(id, 0, 0, 0, texture.width, texture.height, GL_RGBA, GL_FLOAT, rgba.data());
  return id;
}

GLuint ref_sampler(const mesh::TextureRef& ref) {
  GLuint id = 0;
  glCreateSamplers(1, &id);
  const GLint filter = ref.filter == mesh::Filter::nearest ? GL_NEAREST : GL_LINEAR;
  glSamplerParameteri(id, GL_TEXTURE_MIN_FILTER, filter);
  glSamplerParameteri(id, GL_TEXTURE_MAG_FILTER, filter);
  glSamplerParameteri(id, GL_TEXTURE_WRAP_S, gl_wrap(ref.wrap_s));
  glSamplerParameteri(id, GL_TEXTURE_WRAP_T, gl_wrap(ref.wrap_t));
  return id;
}

}  // namespace

BaseColour::~BaseColour() { release(); }

void BaseColour::release() {
  for (GLuint* buffer : {&materials_, &uv_, &triangle_material_, &vertex_colour_, &first_corner_, &draw_indices_})
    delete_buffer(*buffer);
  if (corner_vao_ != 0) glDeleteVertexArrays(1, &corner_vao_);
  corner_vao_ = 0;
  corner_count_ = 0;
  for (GLuint& texture : textures_) delete_texture(texture);
  if (!samplers_.empty()) glDeleteSamplers(static_cast<GLsizei>(samplers_.size()), samplers_.data());
  textures_.clear();
  samplers_.clear();
  slot_image_.clear();
}

void BaseColour::set_mesh(const mesh::Mesh& mesh) {
  release();
  if (!mesh.textured()) return;
  std::vector<std::tuple<int, mesh::Wrap, mesh::Wrap, mesh::Filter>> slots;
  std::vector<GpuMaterial> materials;
  for (const mesh::Material& material : mesh.materials) {
    GpuMaterial m{glm::vec4(material.base_color_factor, 0.0f), {}, {}, glm::ivec4(-1, 0, 0, 0)};
    affine_transform(material.base_color.transform, m);
    if (material.textured()) {
      const mesh::TextureRef& ref = material.base_color;
      const auto key = std::make_tuple(ref.image, ref.wrap_s, ref.wrap_t, ref.filter);
      std::size_t slot = 0;
      while (slot < slots.size() && slots[slot] != key) ++slot;
      if (slot == slots.size()) {
        if (slots.size() == kMaxTextureSlots)
          fail("renderer: the mesh's materials use more than " + std::to_string(kMaxTextureSlots) + " textures");
        slots.push_back(key);
        samplers_.push_back(ref_sampler(ref));
        slot_image_.push_back(ref.image);
      }
      m.slot.x = static_cast<int>(slot);
    }
    materials.push_back(m);
  }
  for (const mesh::Texture& texture : mesh.textures) textures_.push_back(rgb_texture(texture));
  materials_ = make_buffer(static_cast<GLsizeiptr>(materials.size() * sizeof(GpuMaterial)), materials.data(), 0);
  uv_ = make_buffer(static_cast<GLsizeiptr>(mesh.base_color_uv.size() * sizeof(glm::vec2)), mesh.base_color_uv.data(), 0);
  triangle_material_ = make_buffer(static_cast<GLsizeiptr>(mesh.triangle_material.size() * sizeof(std::uint32_t)),
                                   mesh.triangle_material.data(), 0);
  has_vertex_colour_ = !mesh.vertex_color.empty();
  vertex_colour_ = make_buffer(static_cast<GLsizeiptr>(mesh.vertex_color.size() * sizeof(glm::vec3)), mesh.vertex_color.data(), 0);
  upload_corners(mesh);
  check_gl("uploading base colour textures");
}

void BaseColour::upload_corners(const mesh::Mesh& mesh) {
  const TexturedCorners corners = textured_corners(mesh);
  first_corner_ = make_buffer(static_cast<GLsizeiptr>(corners.first_corner.size() * sizeof(std::uint32_t)),
                              corners.first_corner.data(), 0);
  draw_indices_ = make_buffer(static_cast<GLsizeiptr>(corners.draw_vertex.size() * sizeof(std::uint32_t)),
                              corners.draw_vertex.data(), 0);
  corner_count_ = static_cast<GLsizei>(corners.draw_vertex.size());
  glCreateVertexArrays(1, &corner_vao_);
  glVertexArrayVertexBuffer(corner_vao_, 0, first_corner_, 0, sizeof(std::uint32_t));
  glVertexArrayAttribIFormat(corner_vao_, kCornerLocation, 1, GL_UNSIGNED_INT, 0);
  glVertexArrayAttribBinding(corner_vao_, kCornerLocation, 0);
  glEnableVertexArrayAttrib(corner_vao_, kCornerLocation);
  glVertexArrayElementBuffer(corner_vao_, draw_indices_);
}

std::string BaseColour::defines() const {
  return "#define TEXTURED 1\n#define TEXTURE_SLOTS " + std::to_string(std::max<std::size_t>(samplers_.size(), 1)) + "\n";
}

void BaseColour::bind(const Program& program) const {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kMaterialsBinding, materials_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBaseUvBinding, uv_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kTriangleMaterialBinding, triangle_material_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kVertexColourBinding, vertex_colour_);
  for (std::size_t slot = 0; slot < samplers_.size(); ++slot) {
    glBindTextureUnit(kFirstSlotUnit + static_cast<GLuint>(slot), textures_[static_cast<std::size_t>(slot_image_[slot])]);
    glBindSampler(kFirstSlotUnit + static_cast<GLuint>(slot), samplers_[slot]);
  }
  glUniform1i(program.uniform("has_vertex_colour"), has_vertex_colour_ ? 1 : 0);
}

void BaseColour::draw_corners(const FrameCore& core, const Program& program, const TriangleRuns* runs) const {
  bind(program);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kIndicesBinding, core.indices);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPositionsBinding, core.positions);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kAlbedoBinding, core.albedo);
  glBindVertexArray(corner_vao_);
  // The draw's index list has three entries per mesh triangle, in triangle order.
  draw_indexed_runs(program, runs, static_cast<std::uint64_t>(corner_count_) / 3);
}

}  // namespace prt::render
