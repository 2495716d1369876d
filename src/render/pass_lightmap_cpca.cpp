// The compressed texel (CPCA lightmap) pass (renderer.h, PASSES: prt_lightmap_cpca): a texel .cprt drawn
// in its compressed form, never decompressed.
//
// On the GPU, uploaded once: per non-empty texel (the model's points, compress::point_blocks order) its
// cluster id, its N weights (float32) and its texel index; a W x H RGBA32F "shaded lightmap" with a full
// mip chain, and a scratch texture of the same shape for the mip steps. Per frame, on the CPU, the
// clusters' K (N + 1) products with the object-frame sky (cpca_products, as the per-vertex CPCA pass;
// with discs and a model holding the bounce-only part, plus that part's products with the discs' SH).
// Only when they differ from the last frame's (the lighting, its rotation, the bands or the discs
// changed): prt_lightmap_cpca.comp shades every non-empty texel into level 0 (P_k0 + sum_n w_n P_k(n+1)),
// then lightmap_mip.comp builds the coverage-aware mip chain (lightmap_mips.h's rule, on the GPU). The
// draw (prt_lightmap.vert + prt_lightmap_cpca.frag) samples the shaded lightmap trilinearly at the
// pixel's lightmap UV (level 0 in texel space) and, with discs, adds their direct light per pixel and
// clamps at 0, as the uncompressed lightmap pass (renderer_lightmap.h).
//
// Why shade texels, not pixels: bilinear (and mip) filtering is linear, so filtering the shaded texels
// equals shading the filtered transfer, the uncompressed pass's order, up to float rounding; each texel
// is shaded once per lighting change instead of four times per pixel per frame, no cluster id is ever
// interpolated, and a minified chart is filtered over the same coverage-aware mips.
#include <algorithm>
#include <cstring>

#include <glm/gtc/type_ptr.hpp>

#include "core/error.h"
#include "render/bindings.h"
#include "render/lightmap_mips.h"
#include "render/renderer_cpca.h"
#include "render/renderer_lightmap.h"
#include "render/transfer_pass.h"
#include "transfer/half.h"

namespace prt::render {

namespace lightmap_cpca {  // named: the renderer builds as one unity source, and other passes have k* constants

constexpr GLuint kProductsUnit = 0;    // prt_lightmap_cpca.comp: samplerBuffer products
constexpr GLuint kShadedUnit = 0;      // prt_lightmap_cpca.frag: sampler2D shaded_texels
constexpr GLuint kClustersBinding = 7;
constexpr GLuint kWeightsBinding = 8;
constexpr GLuint kTexelsBinding = 9;
constexpr GLuint kTile = 8;            // lightmap_mip.comp's local size

GLuint storage(const void* data, std::size_t bytes, GLbitfield flags) {
  return make_buffer(static_cast<GLsizeiptr>(std::max<std::size_t>(bytes, 16)), data, flags);
}

GLuint texture_2d(int width, int height, int levels) {
  GLuint texture = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &texture);
  glTextureStorage2D(texture, levels, GL_RGBA32F, width, height);
  glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(texture, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  for (int l = 0; l < levels; ++l) glClearTexImage(texture, l, GL_RGBA, GL_FLOAT, zero);
  return texture;
}

// The texel index (y W + x) of every point of a texel model, checked against the model: its coverage
// has W x H entries, as many non-empty ones as it has points, and every cluster id is < K.
std::vector<std::uint32_t> point_texels(const compress::CompressedTransfer& c, const std::string& origin) {
  const transfer::Header& h = c.source;
  const std::size_t texels = static_cast<std::size_t>(h.texel_width) * h.texel_height, P = c.point_count();
  const std::size_t N = static_cast<std::size_t>(c.pca);
  if (c.coverage.size() != texels || c.cluster.size() != P || c.weights.size() != P * N ||
      c.means.size() != static_cast<std::size_t>(c.clusters) * c.point_dimension() || c.bases.size() != c.means.size() * N)
    fail_file(origin, "compressed lightmap arrays do not match its header");
  std::vector<std::uint32_t> out;
  out.reserve(P);
  for (std::size_t t = 0; t < texels; ++t)
    if (c.coverage[t] != transfer::kTexelEmpty) out.push_back(static_cast<std::uint32_t>(t));
  if (out.size() != P) fail_file(origin, "compressed lightmap's coverage does not match its texel count");
  for (std::uint32_t k : c.cluster)
    if (k >= static_cast<std::uint32_t>(c.clusters)) fail_file(origin, "compressed lightmap has a cluster id out of range");
  return out;
}

// The weights of a float16 model as IEEE binary16 bits, two per uint32 (the lower half first, as GLSL's
// unpackHalf2x16 reads them), each point's N padded to an even count. The weights are float16 values
// already (CompressedTransfer), so the bits are exact.
std::vector<std::uint32_t> packed_half_weights(const compress::CompressedTransfer& c) {
  const std::size_t N = static_cast<std::size_t>(c.pca), pairs = (N + 1) / 2;
  std::vector<std::uint32_t> packed(c.point_count() * pairs, 0u);
  for (std::size_t p = 0; p < c.point_count(); ++p)
    for (std::size_t n = 0; n < N; ++n)
      packed[p * pairs + n / 2] |= std::uint32_t(transfer::float_to_half(c.weights[p * N + n])) << (16 * (n % 2));
  return packed;
}

class LightmapCpcaPass final : public TransferPass {
 public:
  LightmapCpcaPass(const compress::CompressedTransfer& c, const std::string& origin);
  ~LightmapCpcaPass() override;

  const transfer::Header& header() const override { return header_; }
  const char* name() const override { return "lightmap_cpca"; }
  void draw(FrameCore& core, const Frame& frame) override;

 private:
  void shade_texels(FrameCore& core);  // level 0 and the mip chain from this frame's products_
  compress::CompressedTransfer model_;  // means and directions (per-texel arrays dropped after upload)
  transfer::Header header_;
  int width_ = 0, height_ = 0, levels_ = 0, points_ = 0;
  GLuint clusters_ = 0, weights_ = 0, texels_ = 0, products_ = 0, products_view_ = 0, shaded_ = 0, scratch_ = 0;
  std::vector<glm::vec4> products_now_, products_last_;
  bool shaded_valid_ = false;
  bool half_weights_ = false;  // the weights buffer holds float16 pairs (the file's own values, bit for bit)
};

LightmapCpcaPass::LightmapCpcaPass(const compress::CompressedTransfer& c, const std::string& origin)
    : TransferPass(origin, c.source.kind), header_(c.source) {
  header_.scalar = transfer::Scalar::float32;
  if (transfer::is_glossy(header_.kind)) fail_file(origin, "glossy texel transfer is not supported");
  const std::vector<std::uint32_t> texels = point_texels(c, origin);
  width_ = static_cast<int>(header_.texel_width);
  height_ = static_cast<int>(header_.texel_height);
  GLint max_side = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_side);
  if (width_ > max_side || height_ > max_side)
    fail_file(origin, "lightmap " + std::to_string(width_) + "x" + std::to_string(height_) + " exceeds this OpenGL's limit (" +
                          std::to_string(max_side) + " texels a side)");
  levels_ = mip_level_count(width_, height_);
  points_ = static_cast<int>(texels.size());
  clusters_ = storage(c.cluster.data(), c.cluster.size() * sizeof(std::uint32_t), 0);
  half_weights_ = c.source.scalar == transfer::Scalar::float16;
  if (half_weights_) {
    const std::vector<std::uint32_t> packed = packed_half_weights(c);
    weights_ = storage(packed.data(), packed.size() * sizeof(std::uint32_t), 0);
  } else {
    weights_ = storage(c.weights.data(), c.weights.size() * sizeof(float), 0);
  }
  texels_ = storage(texels.data(), texels.size() * sizeof(std::uint32_t), 0);
  shaded_ = texture_2d(width_, height_, levels_);
  scratch_ = texture_2d(width_, height_, levels_);
  model_ = cluster_vectors(c);
  check_gl("uploading a compressed lightmap");
}

LightmapCpcaPass::~LightmapCpcaPass() {
  for (GLuint* b : {&clusters_, &weights_, &texels_, &products_}) delete_buffer(*b);
  for (GLuint* t : {&products_view_, &shaded_, &scratch_}) delete_texture(*t);
}

void LightmapCpcaPass::shade_texels(FrameCore& core) {
  const std::size_t bytes = products_now_.size() * sizeof(glm::vec4);
  if (products_ == 0) {
    products_ = storage(nullptr, bytes, GL_DYNAMIC_STORAGE_BIT);  // K (N + 1) vec4, fixed by the model
    glCreateTextures(GL_TEXTURE_BUFFER, 1, &products_view_);
    glTextureBuffer(products_view_, GL_RGBA32F, products_);
  }
  glNamedBufferSubData(products_, 0, static_cast<GLsizeiptr>(bytes), products_now_.data());
  const Program& blend = core.program({"prt_lightmap_cpca.comp"}, "#define PCA " + std::to_string(model_.pca) + "\n" +
                                                                     (half_weights_ ? "#define HALF_WEIGHTS 1\n" : ""));
  glUseProgram(blend.id());
  glUniform1i(blend.uniform("point_count"), points_);
  glUniform1i(blend.uniform("width"), width_);
  glBindTextureUnit(kProductsUnit, products_view_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kClustersBinding, clusters_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kWeightsBinding, weights_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kTexelsBinding, texels_);
  glBindImageTexture(0, shaded_, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  glDispatchCompute(static_cast<GLuint>((points_ + kWorkgroupSize - 1) / kWorkgroupSize), 1, 1);
  // The mip chain: level l -> scratch l + 1 (averaged), scratch l + 1 -> level l + 1 (dilated).
  const Program& reduce = core.program({"lightmap_mip.comp"}, "#define REDUCE 1\n");
  const Program& dilate = core.program({"lightmap_mip.comp"}, "");
  for (int l = 0; l + 1 < levels_; ++l) {
    const GLuint w = static_cast<GLuint>(std::max(1, width_ >> (l + 1))), h = static_cast<GLuint>(std::max(1, height_ >> (l + 1)));
    const std::pair<const Program*, std::pair<GLuint, GLuint>> steps[2] = {{&reduce, {shaded_, scratch_}}, {&dilate, {scratch_, shaded_}}};
    for (const auto& [program, textures] : steps) {
      glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
      glUseProgram(program->id());
      const int source_level = program == &reduce ? l : l + 1;
      glBindImageTexture(0, textures.first, source_level, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
      glBindImageTexture(1, textures.second, l + 1, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
      glDispatchCompute((w + kTile - 1) / kTile, (h + kTile - 1) / kTile, 1);
    }
  }
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  check_gl("shading a compressed lightmap");
}

void LightmapCpcaPass::draw(FrameCore& core, const Frame& frame) {
  const bool bounce = frame.sun && model_.bounce;
  if (frame.sun && header_.kind == transfer::Kind::interreflected && !bounce) warn_no_bounce("");
  std::vector<glm::vec3> discs;
  if (bounce) discs = core.object_disc_lighting(frame.settings, frame.bands);
  cpca_products(model_, core.rotated.data(), bounce ? discs.data() : nullptr, frame.bands, nullptr, products_now_);
  // Once per lighting change: the products say everything the texels' shading depends on.
  if (!shaded_valid_ || products_now_.size() != products_last_.size() ||
      std::memcmp(products_now_.data(), products_last_.data(), products_now_.size() * sizeof(glm::vec4)) != 0) {
    shade_texels(core);
    std::swap(products_now_, products_last_);
    shaded_valid_ = true;
  }
  const std::string defines = std::string(frame.sun ? "#define SUN 1\n" : "") + (frame.texel_space ? "#define TEXEL_SPACE 1\n" : "");
  const Program& p = core.program({"prt_lightmap.vert", "prt_lightmap_cpca.frag"}, defines);
  begin_lightmap_draw(core, p, frame.texel_space);
  glBindTextureUnit(kShadedUnit, shaded_);
  if (frame.sun) core.sun->bind(core, p, sun_surface_, false);  // also the albedo buffer the vertex stage reads
  glDrawArrays(GL_TRIANGLES, 0, core.index_count);
}

}  // namespace lightmap_cpca

std::unique_ptr<TransferPass> make_lightmap_cpca_pass(FrameCore& core, const PassInput& input) {
  if (input.compressed == nullptr || !input.compressed->source.is_texel()) return nullptr;
  check_vertex_count(core, input.compressed->source, input.origin, "compressed lightmap");
  if (core.lightmap_uv_corners != static_cast<std::size_t>(core.index_count))
    fail_file(input.origin, "a texel transfer needs the mesh's lightmap UVs, and this mesh has none");
  return std::make_unique<lightmap_cpca::LightmapCpcaPass>(*input.compressed, input.origin);
}

}  // namespace prt::render
