// The texel (lightmap) pass (renderer.h, PASSES: prt_lightmap; renderer_lightmap.h): the transfer as
// texture arrays sampled per pixel at the lightmap UV; with discs, the bounce-only layers dotted with
// the discs' SH and each disc's direct light per pixel.
#include <glm/gtc/type_ptr.hpp>

#include "core/error.h"
#include "render/bindings.h"
#include "render/renderer_lightmap.h"
#include "render/transfer_pass.h"
#include "sh/basis.h"

namespace prt::render {

namespace {

constexpr GLuint kTransferUnit = 0;            // prt_lightmap.frag: transfer_layers
constexpr GLuint kBounceUnit = 1;              // prt_lightmap.frag: bounce_layers
constexpr GLuint kDiscLightingBinding = 2;     // prt_lightmap.frag: uniform DiscLighting

class LightmapPass final : public TransferPass {
 public:
  explicit LightmapPass(const PassInput& input)
      : TransferPass(input.origin, input.transfer.header.kind), textures_(input.transfer, input.origin) {
    disc_lighting_ = make_buffer(kMaxCoefficients * static_cast<GLsizeiptr>(sizeof(glm::vec4)), nullptr, GL_DYNAMIC_STORAGE_BIT);
  }
  ~LightmapPass() override { delete_buffer(disc_lighting_); }

  const transfer::Header& header() const override { return textures_.header(); }
  const char* name() const override { return "lightmap"; }
  void draw(FrameCore& core, const Frame& frame) override;
  bool draws_runs() const override { return true; }

 private:
  const Program& program(FrameCore& core, int used_count, bool sun, bool bounce, bool texel_space) const {
    const transfer::Header& h = textures_.header();
    return core.program({"prt_lightmap.vert", "prt_lightmap.frag"},
                        "#define CHANNELS " + std::to_string(h.channels) + "\n#define COEFFICIENT_COUNT " +
                            std::to_string(h.bands * h.bands) + "\n#define USED_COUNT " + std::to_string(used_count) +
                            "\n#define LAYERS " + std::to_string(textures_.layers()) + "\n" + (sun ? "#define SUN 1\n" : "") +
                            (bounce ? "#define BOUNCE 1\n" : "") + (texel_space ? "#define TEXEL_SPACE 1\n" : ""));
  }

  LightmapTextures textures_;
  GLuint disc_lighting_ = 0;  // object-frame disc SH (uniform DiscLighting), kMaxBands^2 vec4
};

void LightmapPass::draw(FrameCore& core, const Frame& frame) {
  const bool bounce = frame.sun && textures_.bounce_texture() != 0;
  if (frame.sun && header().kind == transfer::Kind::interreflected && !bounce) warn_no_bounce("");
  const Program& p = program(core, frame.bands * frame.bands, frame.sun, bounce, frame.texel_space);
  begin_lightmap_draw(core, p, frame.texel_space);
  glBindBufferBase(GL_UNIFORM_BUFFER, kObjectLightingBinding, core.object_lighting);
  glBindTextureUnit(kTransferUnit, textures_.transfer_texture());
  if (frame.sun) core.sun->bind(core, p, sun_surface_, false);  // also the albedo buffer the vertex stage reads
  if (bounce) {
    // The discs' SH in the object frame, first `bands` bands, for the bounce-only layers.
    const std::vector<glm::vec3> discs = core.object_disc_lighting(frame.settings, frame.bands);
    std::vector<glm::vec4> upload(discs.size());
    for (std::size_t i = 0; i < discs.size(); ++i) upload[i] = glm::vec4(discs[i], 0.0f);
    glNamedBufferSubData(disc_lighting_, 0, static_cast<GLsizeiptr>(upload.size() * sizeof(glm::vec4)), upload.data());
    glBindBufferBase(GL_UNIFORM_BUFFER, kDiscLightingBinding, disc_lighting_);
    glBindTextureUnit(kBounceUnit, textures_.bounce_texture());
  }
  // Corners 3 first .. 3 (first + count) - 1 of each run (the vertex stage reads corner gl_VertexID).
  draw_runs(p, frame.triangles, static_cast<std::uint64_t>(core.index_count) / 3, [](std::uint64_t first, std::uint64_t count) {
    glDrawArrays(GL_TRIANGLES, static_cast<GLint>(3 * first), static_cast<GLsizei>(3 * count));
  });
}

}  // namespace

std::unique_ptr<TransferPass> make_lightmap_pass(FrameCore& core, const PassInput& input) {
  if (input.compressed != nullptr || !input.transfer.header.is_texel()) return nullptr;
  check_vertex_count(core, input.transfer.header, input.origin);
  if (core.lightmap_uv_corners != static_cast<std::size_t>(core.index_count))
    fail_file(input.origin, "a texel transfer needs the mesh's lightmap UVs, and this mesh has none");
  return std::make_unique<LightmapPass>(input);
}

}  // namespace prt::render
