// The diffuse per-vertex pass (renderer.h, PASSES: prt_diffuse): transfer . lighting per vertex,
// interpolated; with discs, their bounce light per vertex (on the CPU) and their direct light per pixel
// (SunLight::draw_deferred); on a textured mesh, albedo-free per vertex and the base colour per pixel.
#include <cstdio>

#include <glm/gtc/type_ptr.hpp>
#include <glm/matrix.hpp>

#include "render/transfer_pass.h"
#include "shade/shade.h"

namespace prt::render {

namespace {

constexpr GLuint kSunBounceBinding = 7;  // prt_diffuse.vert (SUN): buffer SunBounce

class DiffusePass final : public TransferPass {
 public:
  DiffusePass(const FrameCore& core, const PassInput& input)
      : TransferPass(input.origin, input.transfer.header.kind),
        transfer_(input.transfer, input.origin, input.max_range_bytes),
        interreflected_(input.transfer.header.kind == transfer::Kind::interreflected) {
    if (interreflected_ && !input.transfer.bounce_only.empty()) {
      bounce_.header = input.transfer.header;
      bounce_.header.bounce_only_section = false;
      bounce_.values = input.transfer.bounce_only;
    }
    bounce_buffer_ = make_buffer(static_cast<GLsizeiptr>(std::max<std::size_t>(core.vertex_count * sizeof(glm::vec3), 16)),
                                 nullptr, GL_DYNAMIC_STORAGE_BIT);
  }
  ~DiffusePass() override { delete_buffer(bounce_buffer_); }

  const transfer::Header& header() const override { return transfer_.header(); }
  const char* name() const override { return "diffuse"; }

  // The discs' bounce light T_bounce . L_discs per vertex, L_discs in the object frame; recomputed when
  // the discs, the rotations or the bands change.
  void prepare_sun(FrameCore& core, const Frame& frame) override {
    const glm::dmat3 rotation = glm::transpose(frame.settings.object_rotation) * frame.settings.environment_rotation;
    if (bounce_version_ == core.sun->version() && bounce_rotation_ == rotation && bounce_bands_ == frame.bands) return;
    bounce_version_ = core.sun->version();
    bounce_rotation_ = rotation;
    bounce_bands_ = frame.bands;
    const bool has_bounce = !bounce_.values.empty();
    if (interreflected_ && !has_bounce) warn_no_bounce(" (a version 1 file)");
    std::vector<glm::vec3> bounce(core.vertex_count, glm::vec3(0.0f));
    if (has_bounce) {
      const std::vector<glm::vec3> discs = core.object_disc_lighting(frame.settings, frame.bands);
      sh::RgbCoefficients lighting(frame.bands);
      for (std::size_t i = 0; i < discs.size(); ++i) lighting.values[i] = glm::dvec3(discs[i]);
      bounce = shade::shade_diffuse(bounce_, lighting);
    }
    glNamedBufferSubData(bounce_buffer_, 0, static_cast<GLsizeiptr>(bounce.size() * sizeof(glm::vec3)), bounce.data());
  }

  void draw(FrameCore& core, const Frame& frame) override {
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glBindVertexArray(core.mesh_vao);
    const transfer::Header& h = transfer_.header();
    const Program& program = diffuse_program(core, static_cast<int>(h.channels), static_cast<int>(h.bands * h.bands),
                                             frame.bands * frame.bands, transfer_.chunks(), frame.sun,
                                             textured_ ? core.base_colour.defines() : "");
    glUseProgram(program.id());
    glUniformMatrix4fv(program.uniform("model_view_projection"), 1, GL_FALSE, glm::value_ptr(core.model_view_projection));
    transfer_.bind();
    glUniform1i(program.uniform("vertices_per_chunk"), static_cast<GLint>(transfer_.vertices_per_chunk()));
    glBindBufferBase(GL_UNIFORM_BUFFER, kObjectLightingBinding, core.object_lighting);
    if (frame.sun) {
      core.sun->bind(core, program, sun_surface_, false);
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kSunBounceBinding, bounce_buffer_);
    }
    if (textured_)
      core.base_colour.draw_corners(core, program, frame.triangles);
    else
      core.draw_mesh_elements(program, frame.triangles);
    if (frame.sun) core.sun->draw_deferred(core, frame.settings, sun_surface_, textured_ ? &core.base_colour : nullptr);
  }
  bool draws_runs() const override { return true; }
  bool deferred_sun() const override { return true; }

 private:
  TransferBuffer transfer_;
  bool interreflected_;
  transfer::TransferData bounce_;  // the bounce-only part (values empty if none)
  GLuint bounce_buffer_ = 0;       // the discs' bounce light, x y z floats per vertex
  int bounce_version_ = -1, bounce_bands_ = -1;
  glm::dmat3 bounce_rotation_{1.0};
};

}  // namespace

const Program& diffuse_program(FrameCore& core, int channels, int coefficient_count, int used_count, int chunks, bool sun,
                               const std::string& textured_defines) {
  return core.program({"prt_diffuse.vert", "surface.frag"},
                      "#define CHANNELS " + std::to_string(channels) + "\n#define COEFFICIENT_COUNT " +
                          std::to_string(coefficient_count) + "\n#define USED_COUNT " + std::to_string(used_count) +
                          "\n#define CHUNKS " + std::to_string(chunks) + "\n" + (sun ? "#define SUN 1\n" : "") + textured_defines);
}

std::unique_ptr<TransferPass> make_diffuse_pass(FrameCore& core, const PassInput& input) {
  const transfer::Header& h = input.transfer.header;
  if (input.compressed != nullptr || h.is_texel() || transfer::is_glossy(h.kind)) return nullptr;
  check_vertex_count(core, h, input.origin);
  return std::make_unique<DiffusePass>(core, input);
}

}  // namespace prt::render
