// The renderer's CPCA pass (renderer_cpca.h; renderer.h, PASSES: prt_cpca).
#include "render/renderer_cpca.h"
#include "render/renderer_lightmap.h"

#include <cstdio>

#include <glm/gtc/type_ptr.hpp>
#include <glm/matrix.hpp>

#include "compress/cprt_file.h"
#include "core/error.h"
#include "render/renderer.h"
#include "shade/surface_albedo.h"

namespace prt::render {

namespace {

constexpr GLuint kProductsUnit = 0;      // prt_cpca.comp: samplerBuffer products
constexpr GLuint kClustersBinding = 7;
constexpr GLuint kWeightsBinding = 8;
constexpr GLuint kRadianceBinding = 9;   // prt_cpca.comp (written), prt_cpca.vert (read)

// Diffuse: one rgb per vector.
glm::vec4 diffuse_product(const float* a, int channels, int in_count, int used, const glm::vec3* lighting) {
  glm::vec3 sum(0.0f);
  for (int c = 0; c < 3; ++c) {
    const float* row = a + (channels == 3 ? c : 0) * in_count;
    float s = 0.0f;
    for (int i = 0; i < used; ++i) s += row[i] * lighting[i][c];
    sum[c] = s;
  }
  return glm::vec4(sum, 0.0f);
}

// Glossy: O = B (A L), out_count rgb per vector; `t` is scratch of out_count.
void glossy_product(const float* a, int channels, int in_count, int used, int out_count, const glm::vec3* lighting,
                    const brdf::BrdfMatrix& b, std::vector<glm::vec3>& t, glm::vec4* out) {
  const std::size_t matrix = static_cast<std::size_t>(out_count) * in_count;
  for (int o = 0; o < out_count; ++o)
    for (int c = 0; c < 3; ++c) {
      const float* row = a + (channels == 3 ? c : 0) * matrix + static_cast<std::size_t>(o) * in_count;
      float s = 0.0f;
      for (int i = 0; i < used; ++i) s += row[i] * lighting[i][c];
      t[static_cast<std::size_t>(o)][c] = s;
    }
  for (int o = 0; o < out_count; ++o) {
    glm::vec3 sum(0.0f);
    for (int c = 0; c < 3; ++c) {
      const double* brow = b.for_colour(c) + static_cast<std::size_t>(o) * out_count;
      float s = 0.0f;
      for (int q = 0; q < out_count; ++q) s += static_cast<float>(brow[q]) * t[static_cast<std::size_t>(q)][c];
      sum[c] = s;
    }
    out[o] = glm::vec4(sum, 0.0f);
  }
}

GLuint storage(const void* data, std::size_t bytes, GLbitfield flags) {
  GLuint buffer = 0;
  glCreateBuffers(1, &buffer);
  glNamedBufferStorage(buffer, static_cast<GLsizeiptr>(std::max<std::size_t>(bytes, 16)), data, flags);
  return buffer;
}

}  // namespace

void cpca_products(const compress::CompressedTransfer& c, const glm::vec3* lighting, const glm::vec3* discs, int bands,
                   const brdf::BrdfMatrix* b, std::vector<glm::vec4>& out) {
  const transfer::Header& h = c.source;
  const bool glossy = transfer::is_glossy(h.kind);
  if (glossy && (b == nullptr || b->bands != static_cast<int>(h.bands_out)))
    fail("renderer: compressed glossy transfer needs a BRDF matrix of its output bands");
  const int channels = static_cast<int>(h.channels), in_count = static_cast<int>(h.bands * h.bands), used = bands * bands;
  const int out_count = glossy ? static_cast<int>(h.bands_out * h.bands_out) : 1;
  // Each vector: the transfer's D values (times the sky), then, with the bounce-only part, D more
  // (times the discs' SH): the product is the sum, as shade_diffuse_split adds them.
  const std::size_t D = c.dimension(), E = c.point_dimension(), vectors = static_cast<std::size_t>(c.clusters) * (c.pca + 1);
  const bool bounce = c.bounce && discs != nullptr;
  out.resize(vectors * out_count);
  std::vector<glm::vec3> t(static_cast<std::size_t>(out_count));
  std::vector<glm::vec4> extra(static_cast<std::size_t>(out_count));
  for (std::size_t v = 0; v < vectors; ++v) {
    const std::size_t k = v / (c.pca + 1), j = v % (c.pca + 1);
    const float* a = j == 0 ? &c.means[k * E] : &c.bases[(k * c.pca + j - 1) * E];
    if (glossy) {
      glossy_product(a, channels, in_count, used, out_count, lighting, *b, t, &out[v * out_count]);
      if (!bounce) continue;
      glossy_product(a + D, channels, in_count, used, out_count, discs, *b, t, extra.data());
      for (int o = 0; o < out_count; ++o) out[v * out_count + o] += extra[static_cast<std::size_t>(o)];
    } else {
      out[v] = diffuse_product(a, channels, in_count, used, lighting);
      if (bounce) out[v] += diffuse_product(a + D, channels, in_count, used, discs);
    }
  }
}

compress::CompressedTransfer cluster_vectors(const compress::CompressedTransfer& c) {
  compress::CompressedTransfer out;
  out.source = c.source;
  out.clusters = c.clusters;
  out.pca = c.pca;
  out.bounce = c.bounce;
  out.means = c.means;
  out.bases = c.bases;
  return out;
}

CpcaTransfer::CpcaTransfer(const compress::CompressedTransfer& c, const std::string& origin) : header_(c.source) {
  header_.scalar = transfer::Scalar::float32;
  const std::size_t P = static_cast<std::size_t>(c.source.vertex_count), N = static_cast<std::size_t>(c.pca);
  if (c.cluster.size() != P || c.weights.size() != P * N || c.means.size() != static_cast<std::size_t>(c.clusters) * c.point_dimension() ||
      c.bases.size() != c.means.size() * N)
    fail_file(origin, "compressed transfer arrays do not match its header");
  clusters_ = storage(c.cluster.data(), c.cluster.size() * sizeof(std::uint32_t), 0);
  radiance_ = storage(nullptr, P * sizeof(glm::vec4), 0);
  weights_ = storage(c.weights.data(), c.weights.size() * sizeof(float), 0);
  vertex_bytes_ = (c.cluster.size() + c.weights.size()) * 4 + P * sizeof(glm::vec4);
  model_ = cluster_vectors(c);
  check_gl("uploading a compressed transfer");
}

CpcaTransfer::~CpcaTransfer() {
  for (GLuint* b : {&products_, &clusters_, &weights_, &radiance_})
    if (*b != 0) glDeleteBuffers(1, b);
  if (products_view_ != 0) glDeleteTextures(1, &products_view_);
}

void CpcaTransfer::prepare(const glm::vec3* lighting, const glm::vec3* discs, int bands) {
  cpca_products(model_, lighting, discs, bands, has_brdf_ ? &brdf_ : nullptr, scratch_);
  const std::size_t bytes = scratch_.size() * sizeof(glm::vec4);
  if (products_ == 0 || products_bytes_ != bytes) {
    if (products_ != 0) glDeleteBuffers(1, &products_);
    products_ = storage(nullptr, bytes, GL_DYNAMIC_STORAGE_BIT);
    products_bytes_ = bytes;
    if (products_view_ == 0) glCreateTextures(GL_TEXTURE_BUFFER, 1, &products_view_);
    glTextureBuffer(products_view_, GL_RGBA32F, products_);
  }
  glNamedBufferSubData(products_, 0, static_cast<GLsizeiptr>(bytes), scratch_.data());
  glBindTextureUnit(kProductsUnit, products_view_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kClustersBinding, clusters_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kWeightsBinding, weights_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kRadianceBinding, radiance_);
}

std::size_t CpcaTransfer::gpu_bytes() const {
  const std::size_t out_count = transfer::is_glossy(header_.kind) ? header_.bands_out * header_.bands_out : 1;
  return vertex_bytes_ + static_cast<std::size_t>(model_.clusters) * (model_.pca + 1) * out_count * sizeof(glm::vec4);
}

int add_scene_transfer(Renderer& renderer, const SceneInputs& scene, std::size_t i) {
  const compress::CompressedTransfer* model = i < scene.compressed.size() ? scene.compressed[i].get() : nullptr;
  const int index = renderer.add(scene.transfers[i], model, scene.transfer_paths[i]);
  renderer.set_textured(index, scene.mesh.textured() && shade::baked_with_mesh_albedo(scene.mesh, scene.transfers[i].header));
  return index;
}

namespace {

// ", CPCA K 128 N 8, 2.9 MB, error 1.23% (radiance 0.50%)": the model's payload and recorded errors.
std::string cpca_label(const compress::CompressedTransfer& c) {
  char text[160];
  std::snprintf(text, sizeof text, ", CPCA K %d N %d, %.1f MB, error %.2f%%", c.clusters, c.pca, compress::payload_bytes(c) * 1e-6,
                100.0 * c.total.transfer_relative());
  std::string label = text;
  if (c.has_radiance_error) {
    std::snprintf(text, sizeof text, " (radiance %.2f%%)", 100.0 * c.total.radiance_relative());
    label += text;
  }
  return label;
}

}  // namespace

std::string transfer_memory_label(const SceneInputs& scene, std::size_t i) {
  if (i < scene.compressed.size() && scene.compressed[i]) return cpca_label(*scene.compressed[i]);
  if (scene.transfers[i].header.is_texel()) return lightmap_memory_label(scene.transfers[i].header);
  char text[160];
  std::snprintf(text, sizeof text, ", %.1f MB", compress::uncompressed_bytes(scene.transfers[i].header, transfer::Scalar::float32) * 1e-6);
  return text;
}

}  // namespace prt::render
