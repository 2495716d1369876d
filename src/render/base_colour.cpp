// A textured mesh's base colour on the GPU (base_colour.h).
#include "render/base_colour.h"

#include <string>
#include <vector>

#include <glm/vec4.hpp>

#include "core/error.h"
#include "mesh/texture.h"
#include "render/bindings.h"
#include "render/frame_core.h"

namespace prt::render {

namespace {

constexpr GLuint kMaterialsBinding = 12, kBaseUvBinding = 13, kTriangleMaterialBinding = 14, kVertexColourBinding = 15;
constexpr GLuint kTexelsUnit = 15;

// std430 layout of base_colour.glsl's Material.
struct GpuMaterial {
  glm::vec4 factor;
  glm::vec4 transform_u, transform_v;  // u' = dot(transform_u.xyz, (u, v, 1)), v' likewise
  glm::ivec4 image;                    // first texel, width, height, textured
  glm::ivec4 sampler;                  // wrap u, wrap v, nearest, unused
};

// The affine map of the material's KHR_texture_transform, from mesh::transform_uv at three points.
void affine_transform(const mesh::TextureTransform& transform, GpuMaterial& m) {
  const glm::vec2 o = mesh::transform_uv(transform, glm::vec2(0.0f));
  const glm::vec2 du = mesh::transform_uv(transform, glm::vec2(1.0f, 0.0f)) - o;
  const glm::vec2 dv = mesh::transform_uv(transform, glm::vec2(0.0f, 1.0f)) - o;
  m.transform_u = glm::vec4(du.x, dv.x, o.x, 0.0f);
  m.transform_v = glm::vec4(du.y, dv.y, o.y, 0.0f);
}

std::vector<GpuMaterial> gpu_materials(const mesh::Mesh& mesh, const std::vector<GLint>& first_texel) {
  std::vector<GpuMaterial> out;
  for (const mesh::Material& material : mesh.materials) {
    GpuMaterial m{};
    m.factor = glm::vec4(material.base_color_factor, 0.0f);
    affine_transform(material.base_color.transform, m);
    if (material.textured()) {
      const auto image = static_cast<std::size_t>(material.base_color.image);
      const mesh::Texture& texture = mesh.textures[image];
      m.image = glm::ivec4(first_texel[image], texture.width, texture.height, 1);
      m.sampler = glm::ivec4(static_cast<int>(material.base_color.wrap_s), static_cast<int>(material.base_color.wrap_t),
                             material.base_color.filter == mesh::Filter::nearest ? 1 : 0, 0);
    }
    out.push_back(m);
  }
  return out;
}

}  // namespace

BaseColour::~BaseColour() {
  for (GLuint* buffer : {&materials_, &uv_, &triangle_material_, &vertex_colour_, &texel_buffer_}) delete_buffer(*buffer);
  delete_texture(texels_);
}

void BaseColour::set_mesh(const mesh::Mesh& mesh) {
  for (GLuint* buffer : {&materials_, &uv_, &triangle_material_, &vertex_colour_, &texel_buffer_}) delete_buffer(*buffer);
  delete_texture(texels_);
  if (!mesh.textured()) return;
  std::vector<GLint> first_texel;
  std::vector<float> rgb;
  for (const mesh::Texture& texture : mesh.textures) {
    first_texel.push_back(static_cast<GLint>(rgb.size() / 3));
    rgb.insert(rgb.end(), texture.rgb.begin(), texture.rgb.end());
  }
  GLint max_texels = 0;
  glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &max_texels);
  if (rgb.size() / 3 > static_cast<std::size_t>(max_texels))
    fail("renderer: the mesh's textures hold " + std::to_string(rgb.size() / 3) + " texels; this OpenGL takes at most " +
         std::to_string(max_texels) + " in one buffer texture");
  const std::vector<GpuMaterial> materials = gpu_materials(mesh, first_texel);
  materials_ = make_buffer(static_cast<GLsizeiptr>(materials.size() * sizeof(GpuMaterial)), materials.data(), 0);
  uv_ = make_buffer(static_cast<GLsizeiptr>(mesh.base_color_uv.size() * sizeof(glm::vec2)), mesh.base_color_uv.data(), 0);
  triangle_material_ = make_buffer(static_cast<GLsizeiptr>(mesh.triangle_material.size() * sizeof(std::uint32_t)),
                                   mesh.triangle_material.data(), 0);
  has_vertex_colour_ = !mesh.vertex_color.empty();
  vertex_colour_ = make_buffer(static_cast<GLsizeiptr>(mesh.vertex_color.size() * sizeof(glm::vec3)), mesh.vertex_color.data(), 0);
  texel_buffer_ = make_buffer(static_cast<GLsizeiptr>(rgb.size() * sizeof(float)), rgb.data(), 0);
  glCreateTextures(GL_TEXTURE_BUFFER, 1, &texels_);
  glTextureBuffer(texels_, GL_RGB32F, texel_buffer_);
  check_gl("uploading base colour textures");
}

void BaseColour::bind(const Program& program) const {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kMaterialsBinding, materials_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBaseUvBinding, uv_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kTriangleMaterialBinding, triangle_material_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kVertexColourBinding, vertex_colour_);
  glBindTextureUnit(kTexelsUnit, texels_);
  glUniform1i(program.uniform("has_vertex_colour"), has_vertex_colour_ ? 1 : 0);
}

void BaseColour::draw_deferred(FrameCore& core, const FrameSettings& settings) const {
  const Program& program = core.program({"sun_fullscreen.vert", "prt_texture.frag"});
  core.begin_deferred(program, settings);
  bind(program);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kIndicesBinding, core.indices);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPositionsBinding, core.positions);
  core.end_deferred();
}

}  // namespace prt::render
