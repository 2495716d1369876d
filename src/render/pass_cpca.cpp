// The compressed (CPCA) pass (renderer.h, PASSES: prt_cpca; renderer_cpca.h): per frame the clusters'
// products with the lighting on the CPU, a compute pass that blends them per vertex, a draw that
// interpolates; with discs, their bounce light in the products (the model's bounce-only part) and their
// direct light per pixel (diffuse: SunLight::draw_deferred) or in the draw (glossy: prt_cpca_sun.frag).
#include <glm/gtc/type_ptr.hpp>

#include "core/error.h"
#include "render/bindings.h"
#include "render/renderer_cpca.h"
#include "render/transfer_pass.h"

namespace prt::render {

namespace {


class CpcaPass final : public TransferPass {
 public:
  explicit CpcaPass(const PassInput& input)
      : TransferPass(input.origin, input.compressed->source.kind), transfer_(*input.compressed, input.origin) {
    const transfer::Kind kind = input.compressed->source.kind;
    // The discs' bounce light comes from the model's bounce-only part in the products; an interreflected
    // model without it leaves that light out, with a warning.
    missing_bounce_ = (kind == transfer::Kind::interreflected || kind == transfer::Kind::glossy_interreflected) && !input.compressed->bounce;
  }

  const transfer::Header& header() const override { return transfer_.header(); }
  const char* name() const override { return "cpca"; }
  void set_brdf(const brdf::BrdfMatrix& matrix) override { transfer_.set_brdf(matrix); }
  void prepare_sun(FrameCore&, const Frame&) override {
    if (missing_bounce_) warn_no_bounce(" (a version 1 file)");
  }
  void draw(FrameCore& core, const Frame& frame) override;

 private:
  CpcaTransfer transfer_;
  bool missing_bounce_ = false;
};

void CpcaPass::draw(FrameCore& core, const Frame& frame) {
  CpcaTransfer& t = transfer_;
  const bool glossy = transfer::is_glossy(t.header().kind);
  if (glossy && !t.has_brdf()) fail("renderer: glossy transfer " + std::to_string(frame.index) + " has no BRDF matrix (set_brdf)");
  // With discs: their SH in the object frame for the bounce-only part.
  std::vector<glm::vec3> discs;
  if (frame.sun && t.has_bounce()) discs = core.object_disc_lighting(frame.settings, frame.bands);
  // Per vertex: blend the products (and, glossy, evaluate toward the eye) into the radiance buffer.
  t.prepare(core.rotated.data(), discs.empty() ? nullptr : discs.data(), frame.bands);
  const int out_bands = glossy ? static_cast<int>(t.header().bands_out) : 0;
  const Program& compute =
      core.program({"prt_cpca.comp"}, "#define PCA " + std::to_string(t.pca()) + "\n#define OUT_BANDS " + std::to_string(out_bands) + "\n");
  glUseProgram(compute.id());
  const glm::vec3 eye_object = core.eye_object(frame.settings);
  glUniform3f(compute.uniform("eye_object"), eye_object.x, eye_object.y, eye_object.z);
  glUniform1i(compute.uniform("vertex_count"), static_cast<GLint>(core.vertex_count));
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPositionsBinding, core.positions);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kNormalsBinding, core.normals);
  glDispatchCompute(static_cast<GLuint>((core.vertex_count + kWorkgroupSize - 1) / kWorkgroupSize), 1, 1);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);

  // Draw with the per-vertex radiance, interpolated as the diffuse pass's. With discs, diffuse: the
  // deferred pass adds their direct light per pixel as for uncompressed transfer; glossy:
  // prt_cpca_sun.frag evaluates the BRDF toward the eye in the draw itself.
  const bool forward_sun = frame.sun && glossy;
  const bool textured = textured_ && !glossy;  // the albedo split holds for diffuse transfer only
  const Program& draw = forward_sun ? core.program({"prt_cpca.vert", "prt_cpca_sun.frag"}, "#define SUN 1\n")
                                    : core.program({"prt_cpca.vert", "surface.frag"}, textured ? core.base_colour.defines() : "");
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glBindVertexArray(core.mesh_vao);
  glUseProgram(draw.id());
  glUniformMatrix4fv(draw.uniform("model_view_projection"), 1, GL_FALSE, glm::value_ptr(core.model_view_projection));
  if (forward_sun) {
    core.sun->bind(core, draw, sun_surface_, true);
    glUniform3f(draw.uniform("eye_object"), eye_object.x, eye_object.y, eye_object.z);
  }
  if (textured)
    core.base_colour.draw_corners(core, draw);  // prt_cpca.vert reads the radiance prepare() bound
  else
    core.draw_mesh_elements();
  if (frame.sun && !glossy) core.sun->draw_deferred(core, frame.settings, sun_surface_, textured ? &core.base_colour : nullptr);
}

}  // namespace

std::unique_ptr<TransferPass> make_cpca_pass(FrameCore& core, const PassInput& input) {
  if (input.compressed == nullptr) return nullptr;
  check_vertex_count(core, input.compressed->source, input.origin, "compressed transfer");
  return std::make_unique<CpcaPass>(input);
}

}  // namespace prt::render
