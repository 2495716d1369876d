// The renderer's texel (lightmap) transfer pass (renderer.h, PASSES: prt_lightmap; renderer_lightmap.h).
#include "render/renderer_lightmap.h"

#include <algorithm>
#include <cstdio>

#include <glm/gtc/type_ptr.hpp>
#include <glm/matrix.hpp>

#include "core/error.h"
#include "render/lightmap_mips.h"
#include "render/renderer_sun.h"
#include "sh/basis.h"
#include "sh/rotation.h"

namespace prt::render {

namespace {

constexpr int kMaxCoefficients = sh::kMaxBands * sh::kMaxBands;
constexpr GLuint kTransferUnit = 0;            // prt_lightmap.frag: transfer_layers
constexpr GLuint kBounceUnit = 1;              // prt_lightmap.frag: bounce_layers
constexpr GLuint kObjectLightingBinding = 0;   // uniform Lighting (Renderer::update_lighting)
constexpr GLuint kDiscLightingBinding = 2;     // prt_lightmap.frag: uniform DiscLighting
constexpr GLuint kIndicesBinding = 3;          // prt_lightmap.vert
constexpr GLuint kPositionsBinding = 4;
constexpr GLuint kNormalsBinding = 5;
constexpr GLuint kUvBinding = 10;

}  // namespace

int lightmap_layers(std::uint64_t values_per_texel) { return static_cast<int>((values_per_texel + 3) / 4); }

std::string lightmap_memory_label(const transfer::Header& header) {
  const double texels = static_cast<double>(header.texel_width) * header.texel_height;
  const double bytes = texels * lightmap_layers(header.values_per_vertex()) * (header.scalar == transfer::Scalar::float16 ? 8 : 16) *
                       (header.bounce_only_section ? 2 : 1) * 4.0 / 3.0;  // with the mip chain
  char text[96];
  std::snprintf(text, sizeof text, ", lightmap %ux%u, %.1f MB", header.texel_width, header.texel_height, bytes * 1e-6);
  return text;
}

LightmapTextures::LightmapTextures(const transfer::TransferData& transfer, const std::string& origin)
    : header_(transfer.header) {
  if (!header_.is_texel()) fail_file(origin, "not a texel (lightmap) transfer");
  if (transfer::is_glossy(header_.kind)) fail_file(origin, "glossy texel transfer is not supported");
  const std::uint64_t texels = static_cast<std::uint64_t>(header_.texel_width) * header_.texel_height;
  const std::uint64_t per_texel = header_.values_per_vertex();
  if (transfer.values.size() != texels * per_texel)
    fail_file(origin, "texel transfer value count does not match its header");
  if (!transfer.bounce_only.empty() && transfer.bounce_only.size() != transfer.values.size())
    fail_file(origin, "texel transfer's bounce-only section does not match its header");
  layers_ = lightmap_layers(per_texel);
  GLint max_side = 0, max_layers = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_side);
  glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &max_layers);
  if (header_.texel_width > static_cast<std::uint32_t>(max_side) || header_.texel_height > static_cast<std::uint32_t>(max_side) ||
      layers_ > max_layers)
    fail_file(origin, "lightmap " + std::to_string(header_.texel_width) + "x" + std::to_string(header_.texel_height) + " with " +
                          std::to_string(layers_) + " layers exceeds this OpenGL's limits (" + std::to_string(max_side) +
                          " texels a side, " + std::to_string(max_layers) + " layers)");
  const bool half = header_.scalar == transfer::Scalar::float16;
  const GLenum format = half ? GL_RGBA16F : GL_RGBA32F;
  if (!transfer.coverage.empty() && transfer.coverage.size() != texels)
    fail_file(origin, "texel transfer's coverage mask does not match its header");
  transfer_ = upload(transfer.values, transfer.coverage, format);
  if (!transfer.bounce_only.empty()) bounce_ = upload(transfer.bounce_only, transfer.coverage, format);
  // The mip chain adds at most a third.
  bytes_ = static_cast<std::size_t>(texels * static_cast<std::uint64_t>(layers_) * (half ? 8 : 16) * 4 / 3) * (bounce_ != 0 ? 2 : 1);
  check_gl("uploading a texel transfer");
}

// One RGBA layer at a time: layer k of texel b = values[b * V + 4k .. 4k + 3] (zero past V), then its
// mip chain (lightmap_mips.h), filled where the coverage mask is not empty.
GLuint LightmapTextures::upload(const std::vector<float>& values, const std::vector<std::uint8_t>& coverage,
                                GLenum internal_format) {
  const GLsizei width = static_cast<GLsizei>(header_.texel_width), height = static_cast<GLsizei>(header_.texel_height);
  const std::size_t texels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  const std::size_t per_texel = static_cast<std::size_t>(header_.values_per_vertex());
  const int levels = mip_level_count(width, height);
  GLuint texture = 0;
  glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &texture);
  glTextureStorage3D(texture, levels, internal_format, width, height, layers_);
  glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(texture, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  MipLevel level;
  for (int k = 0; k < layers_; ++k) {
    level.width = width;
    level.height = height;
    level.rgba.resize(texels * 4);
    level.filled.resize(texels);
    for (std::size_t b = 0; b < texels; ++b) {
      level.filled[b] = coverage.empty() || coverage[b] != transfer::kTexelEmpty;
      for (std::size_t j = 0; j < 4; ++j) {
        const std::size_t value = 4 * static_cast<std::size_t>(k) + j;
        level.rgba[4 * b + j] = value < per_texel ? values[b * per_texel + value] : 0.0f;
      }
    }
    for (int l = 0; l < levels; ++l) {
      if (l > 0) level = next_mip_level(level);
      glTextureSubImage3D(texture, l, 0, 0, k, level.width, level.height, 1, GL_RGBA, GL_FLOAT, level.rgba.data());
    }
  }
  return texture;
}

LightmapTextures::~LightmapTextures() {
  delete_texture(transfer_);
  delete_texture(bounce_);
}

// ---------------------------------------------------------------------------------------------------
Renderer::LightmapPass::LightmapPass() {
  glCreateBuffers(1, &disc_lighting);
  glNamedBufferStorage(disc_lighting, kMaxCoefficients * static_cast<GLsizeiptr>(sizeof(glm::vec4)), nullptr,
                       GL_DYNAMIC_STORAGE_BIT);
}

Renderer::LightmapPass::~LightmapPass() {
  textures.clear();
  delete_buffer(uv_buffer);
  delete_buffer(disc_lighting);
}

void Renderer::LightmapPass::set_mesh(const mesh::Mesh& mesh) {
  textures.clear();
  warned.clear();
  delete_buffer(uv_buffer);
  uv_corners = mesh.has_lightmap_uv() ? mesh.lightmap_uv.size() : 0;
  if (uv_corners == 0) return;
  glCreateBuffers(1, &uv_buffer);
  glNamedBufferStorage(uv_buffer, static_cast<GLsizeiptr>(uv_corners * sizeof(glm::vec2)), mesh.lightmap_uv.data(), 0);
}

int Renderer::add_lightmap(const transfer::TransferData& transfer, const std::string& origin) {
  if (!has_mesh_) fail("renderer: set a mesh before its transfer");
  if (transfer.header.vertex_count != vertex_count_)
    fail_file(origin, "transfer has " + std::to_string(transfer.header.vertex_count) + " vertices, the mesh " +
                          std::to_string(vertex_count_));
  if (lightmap_->uv_corners != static_cast<std::size_t>(index_count_))
    fail_file(origin, "a texel transfer needs the mesh's lightmap UVs, and this mesh has none");
  LightmapPass& pass = *lightmap_;
  pass.textures.resize(transfers_.size());
  pass.warned.resize(transfers_.size(), false);
  pass.textures.push_back(std::make_unique<LightmapTextures>(transfer, origin));
  pass.warned.push_back(false);
  transfers_.push_back(nullptr);
  // The sun pass keeps per-transfer state too; it computes no per-vertex bounce light for a lightmap
  // (its bounce-only layers are shaded per pixel here), so it gets neither values nor the
  // interreflected flag.
  SunPass::PerTransfer sun;
  sun.origin = origin;
  sun.shadows = transfer.header.kind != transfer::Kind::unshadowed;
  sun_->transfers.push_back(std::move(sun));
  brdf_buffers_.push_back(0);
  brdf_bands_.push_back(0);
  return static_cast<int>(transfers_.size()) - 1;
}

bool Renderer::is_lightmap(int index) const {
  const auto& textures = lightmap_->textures;
  return index >= 0 && static_cast<std::size_t>(index) < textures.size() && textures[static_cast<std::size_t>(index)] != nullptr;
}

const transfer::Header& Renderer::lightmap_header(int index) const {
  return lightmap_->textures[static_cast<std::size_t>(index)]->header();
}

const Program& Renderer::lightmap_program(const transfer::Header& header, int used_count, bool sun, bool bounce,
                                          bool texel_space) {
  const int channels = static_cast<int>(header.channels), coefficients = static_cast<int>(header.bands * header.bands);
  const int layers = lightmap_layers(header.values_per_vertex());
  const auto key = std::make_tuple(channels, coefficients, used_count, layers, sun, bounce, texel_space);
  auto& programs = lightmap_->programs;
  auto found = programs.find(key);
  if (found == programs.end()) {
    const std::string defines = "#define CHANNELS " + std::to_string(channels) + "\n#define COEFFICIENT_COUNT " +
                                std::to_string(coefficients) + "\n#define USED_COUNT " + std::to_string(used_count) +
                                "\n#define LAYERS " + std::to_string(layers) + "\n" + (sun ? "#define SUN 1\n" : "") +
                                (bounce ? "#define BOUNCE 1\n" : "") + (texel_space ? "#define TEXEL_SPACE 1\n" : "");
    found = programs.emplace(key, Program({"prt_lightmap.vert", "prt_lightmap.frag"}, defines)).first;
  }
  return found->second;
}

// The discs' SH in the object frame, first `bands` bands, for the bounce-only layers.
void Renderer::upload_lightmap_disc_lighting(const FrameSettings& settings, int bands) {
  const glm::mat3 rotation(glm::transpose(settings.object_rotation) * settings.environment_rotation);
  const int count = bands * bands;
  std::vector<glm::vec3> rotated(static_cast<std::size_t>(count));
  sh::rotate_rgb(bands, rotation, sun_->disc_lighting.data(), rotated.data());
  std::vector<glm::vec4> upload(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) upload[static_cast<std::size_t>(i)] = glm::vec4(rotated[static_cast<std::size_t>(i)], 0.0f);
  glNamedBufferSubData(lightmap_->disc_lighting, 0, static_cast<GLsizeiptr>(upload.size() * sizeof(glm::vec4)), upload.data());
}

void Renderer::draw_lightmap(const FrameSettings& settings, int bands, bool sun, bool texel_space) {
  LightmapPass& pass = *lightmap_;
  const LightmapTextures& textures = *pass.textures[static_cast<std::size_t>(settings.transfer)];
  const transfer::Header& header = textures.header();
  const bool bounce = sun && textures.bounce_texture() != 0;
  if (sun && header.kind == transfer::Kind::interreflected && !bounce && !pass.warned[static_cast<std::size_t>(settings.transfer)]) {
    std::fprintf(stderr, "prt: %s: no bounce-only section: the discs' interreflected light is left out; re-bake for it\n",
                 sun_->transfers[static_cast<std::size_t>(settings.transfer)].origin.c_str());
    pass.warned[static_cast<std::size_t>(settings.transfer)] = true;
  }
  const Program& program = lightmap_program(header, bands * bands, sun, bounce, texel_space);
  if (texel_space) {
    glDisable(GL_DEPTH_TEST);  // charts do not overlap (the bake's UV check)
  } else {
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
  }
  glUseProgram(program.id());
  glBindVertexArray(empty_vao_);
  glUniformMatrix4fv(program.uniform("model_view_projection"), 1, GL_FALSE, glm::value_ptr(model_view_projection_));
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kIndicesBinding, indices_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPositionsBinding, positions_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kNormalsBinding, normals_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kUvBinding, pass.uv_buffer);
  glBindBufferBase(GL_UNIFORM_BUFFER, kObjectLightingBinding, object_lighting_);
  glBindTextureUnit(kTransferUnit, textures.transfer_texture());
  if (sun) bind_sun(program, settings, false);  // also the albedo buffer the vertex stage reads
  if (bounce) {
    upload_lightmap_disc_lighting(settings, bands);
    glBindBufferBase(GL_UNIFORM_BUFFER, kDiscLightingBinding, pass.disc_lighting);
    glBindTextureUnit(kBounceUnit, textures.bounce_texture());
  }
  glDrawArrays(GL_TRIANGLES, 0, index_count_);
}

void Renderer::render_texels(const FrameSettings& settings) {
  if (!has_mesh_) fail("renderer: no mesh");
  if (!is_lightmap(settings.transfer)) fail("renderer: transfer " + std::to_string(settings.transfer) + " is not a lightmap");
  const transfer::Header& header = lightmap_header(settings.transfer);
  const int transfer_bands = static_cast<int>(header.bands);
  if (settings.bands < 0 || settings.bands > transfer_bands)
    fail_option("bands", ": must be between 1 and the transfer's " + std::to_string(transfer_bands) + " bands, got " +
         std::to_string(settings.bands));
  const int bands = settings.bands == 0 ? transfer_bands : settings.bands;
  const int width = static_cast<int>(header.texel_width), height = static_cast<int>(header.texel_height);
  resize(width, height);
  view_ = orbit_view(settings.camera, bounds_, width, height, settings.object_rotation);
  model_view_projection_ = glm::mat4(view_.projection * view_.view * view_.model);
  update_lighting(settings.environment_rotation, settings.object_rotation, bands);
  const bool sun = sun_active(settings);
  if (sun) update_sun(settings, bands);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  glViewport(0, 0, width, height);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glDisable(GL_SCISSOR_TEST);
  const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  const GLuint none[4] = {kNoTriangle, 0, 0, 0};
  glClearNamedFramebufferfv(framebuffer_, GL_COLOR, 0, zero);
  glClearNamedFramebufferuiv(framebuffer_, GL_COLOR, 1, none);
  draw_lightmap(settings, bands, sun, true);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  check_gl("rendering lightmap texels");
}

}  // namespace prt::render
