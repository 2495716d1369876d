// The renderer's texel (lightmap) transfer pass (renderer.h, PASSES: prt_lightmap; renderer_lightmap.h).
#include "render/renderer_lightmap.h"

#include <algorithm>
#include <cstdio>

#include <glm/gtc/type_ptr.hpp>
#include <glm/matrix.hpp>

#include "core/error.h"
#include "render/bindings.h"
#include "render/lightmap_mips.h"

namespace prt::render {

namespace {

constexpr GLuint kUvBinding = 10;  // prt_lightmap.vert: LightmapUv

}  // namespace

void begin_lightmap_draw(FrameCore& core, const Program& program, bool texel_space) {
  if (texel_space) {
    glDisable(GL_DEPTH_TEST);  // charts do not overlap (the bake's UV check)
  } else {
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
  }
  glUseProgram(program.id());
  glBindVertexArray(core.empty_vao);
  glUniformMatrix4fv(program.uniform("model_view_projection"), 1, GL_FALSE, glm::value_ptr(core.model_view_projection));
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kIndicesBinding, core.indices);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPositionsBinding, core.positions);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kNormalsBinding, core.normals);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kUvBinding, core.lightmap_uv);
}

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

}  // namespace prt::render
