// The glossy per-vertex pass (renderer.h, PASSES: prt_glossy): per frame O = B (M L) for every vertex
// (prt_glossy.comp), then a draw that evaluates O toward the eye per fragment; with discs, their bounce
// light B (M_bounce L_discs) per vertex, added to O, and their direct light per fragment through the BRDF.
#include <algorithm>
#include <string>

#include <glm/gtc/type_ptr.hpp>
#include <glm/matrix.hpp>

#include "core/error.h"
#include "render/bindings.h"
#include "render/transfer_pass.h"
#include "sh/basis.h"

namespace prt::render {

namespace {

constexpr GLuint kLightingBinding = 0;         // prt_glossy.comp: uniform Lighting (object frame)
constexpr GLuint kBrdfBinding = 1;             // prt_glossy.comp: buffer BrdfMatrix
constexpr GLuint kOutgoingBinding = 2;         // prt_glossy.comp (written), prt_glossy.frag (read)
constexpr GLuint kBounceOutgoingBinding = 6;   // prt_glossy.comp (SUN)
constexpr GLuint kVertexBrdfBinding = 7;       // prt_glossy.comp, prt_glossy.frag (BRDF_TABLE)

// A storage buffer of at least `bytes`, reallocated (contents undefined) only when it grows.
void ensure_buffer(GLuint& buffer, std::size_t& size, std::size_t bytes, GLbitfield flags) {
  if (buffer != 0 && size >= bytes) return;
  delete_buffer(buffer);
  buffer = make_buffer(static_cast<GLsizeiptr>(std::max<std::size_t>(bytes, 16)), nullptr, flags);
  size = bytes;
}

class GlossyPass final : public TransferPass {
 public:
  explicit GlossyPass(const PassInput& input)
      : TransferPass(input.origin, input.transfer.header.kind), transfer_(input.transfer, input.origin, input.max_range_bytes) {
    const transfer::Kind kind = input.transfer.header.kind;
    interreflected_ = kind == transfer::Kind::glossy_interreflected;
    if (interreflected_ && !input.transfer.bounce_only.empty()) {
      transfer::TransferData part;
      part.header = input.transfer.header;
      part.header.bounce_only_section = false;
      part.values = input.transfer.bounce_only;
      bounce_ = std::make_unique<TransferBuffer>(part, input.origin + " (bounce-only part)", input.max_range_bytes);
    }
  }
  ~GlossyPass() override {
    for (GLuint* buffer : {&brdf_, &vertex_brdf_, &outgoing_, &bounce_outgoing_, &disc_lighting_}) delete_buffer(*buffer);
  }

  const transfer::Header& header() const override { return transfer_.header(); }
  const char* name() const override { return "glossy"; }

  void set_brdf(const brdf::BrdfMatrix& matrix) override { set_brdf_table({matrix}, {}); }

  // The matrices back to back in brdf_ (rgb per entry), and with several each vertex's index in vertex_brdf_.
  void set_brdf_table(const std::vector<brdf::BrdfMatrix>& matrices, const std::vector<std::uint32_t>& vertex) override {
    const int n = matrices.front().coefficients();
    const std::size_t block = static_cast<std::size_t>(n) * n;
    std::vector<glm::vec4> entries(block * matrices.size());
    for (std::size_t m = 0; m < matrices.size(); ++m)
      for (int c = 0; c < 3; ++c) {
        const double* b = matrices[m].for_colour(c);
        for (std::size_t i = 0; i < block; ++i) entries[m * block + i][c] = static_cast<float>(b[i]);
      }
    const auto bytes = static_cast<GLsizeiptr>(entries.size() * sizeof(glm::vec4));
    if (brdf_ != 0 && brdf_bands_ == matrices.front().bands && brdf_count_ == matrices.size()) {
      glNamedBufferSubData(brdf_, 0, bytes, entries.data());
    } else {
      delete_buffer(brdf_);
      brdf_ = make_buffer(bytes, entries.data(), GL_DYNAMIC_STORAGE_BIT);
    }
    delete_buffer(vertex_brdf_);
    if (matrices.size() > 1)
      vertex_brdf_ = make_buffer(static_cast<GLsizeiptr>(vertex.size() * sizeof(std::uint32_t)), vertex.data(), 0);
    brdf_bands_ = matrices.front().bands;
    brdf_count_ = matrices.size();
    ++brdf_version_;  // the bounce light goes through B
    check_gl("uploading BRDF matrices");
  }

  void prepare_sun(FrameCore& core, const Frame& frame) override;
  void draw(FrameCore& core, const Frame& frame) override;

 private:
  const Program& compute_program(FrameCore& core, int used_count, int chunks, bool sun) const {
    const transfer::Header& h = transfer_.header();
    return core.program({"prt_glossy.comp"}, "#define CHANNELS " + std::to_string(h.channels) + "\n#define IN_COUNT " +
                                                 std::to_string(h.bands * h.bands) + "\n#define USED_COUNT " +
                                                 std::to_string(used_count) + "\n#define OUT_COUNT " + std::to_string(out_count()) +
                                                 "\n#define CHUNKS " + std::to_string(chunks) + "\n" + (sun ? "#define SUN 1\n" : "") +
                                                 table_define());
  }
  /// "#define BRDF_TABLE 1\n" with several BRDFs, else "".
  std::string table_define() const { return brdf_count_ > 1 ? "#define BRDF_TABLE 1\n" : ""; }
  int out_count() const { return static_cast<int>(transfer_.header().bands_out * transfer_.header().bands_out); }
  /// O (or the bounce) of every vertex into `output`, from `transfer` and the lighting in uniform buffer `lighting`.
  void dispatch(const FrameCore& core, const Program& compute, const TransferBuffer& transfer, GLuint lighting, GLuint output) const {
    glUseProgram(compute.id());
    transfer.bind();
    glUniform1i(compute.uniform("vertices_per_chunk"), static_cast<GLint>(transfer.vertices_per_chunk()));
    glUniform1i(compute.uniform("vertex_count"), static_cast<GLint>(core.vertex_count));
    glBindBufferBase(GL_UNIFORM_BUFFER, kLightingBinding, lighting);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBrdfBinding, brdf_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kOutgoingBinding, output);
    if (vertex_brdf_ != 0) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kVertexBrdfBinding, vertex_brdf_);
  }

  TransferBuffer transfer_;
  bool interreflected_ = false;
  std::unique_ptr<TransferBuffer> bounce_;  // the bounce-only part (null if none)
  GLuint brdf_ = 0;                         // B as vec4 per entry, brdf_count_ of them (0 until set_brdf)
  GLuint vertex_brdf_ = 0;                  // each vertex's index into them (uint), with several; else 0
  int brdf_bands_ = 0, brdf_version_ = 0;
  std::size_t brdf_count_ = 0;
  GLuint outgoing_ = 0;                     // O of every vertex, vec4 per coefficient
  std::size_t outgoing_bytes_ = 0;
  GLuint bounce_outgoing_ = 0;              // the discs' bounce light, vec4 per coefficient per vertex
  std::size_t bounce_outgoing_bytes_ = 0;
  GLuint disc_lighting_ = 0;                // the discs' object-frame SH (uniform Lighting layout)
  int bounce_version_ = -1, bounce_brdf_version_ = -1, bounce_bands_ = -1;
  glm::dmat3 bounce_rotation_{1.0};
};

// The discs' bounce light B (M_bounce L_discs) per vertex (prt_glossy.comp), L_discs in the object frame;
// recomputed when the discs, the BRDF, the rotations or the bands change.
void GlossyPass::prepare_sun(FrameCore& core, const Frame& frame) {
  if (!sun_surface_.has_terms)
    fail("renderer: glossy transfer " + std::to_string(frame.index) + " has no BRDF for the discs' direct light (set_brdf with the Brdf)");
  const glm::dmat3 rotation = glm::transpose(frame.settings.object_rotation) * frame.settings.environment_rotation;
  if (bounce_version_ == core.sun->version() && bounce_brdf_version_ == brdf_version_ && bounce_rotation_ == rotation &&
      bounce_bands_ == frame.bands)
    return;
  bounce_version_ = core.sun->version();
  bounce_brdf_version_ = brdf_version_;
  bounce_rotation_ = rotation;
  bounce_bands_ = frame.bands;
  if (interreflected_ && bounce_ == nullptr) warn_no_bounce(" (a version 1 file)");
  ensure_buffer(bounce_outgoing_, bounce_outgoing_bytes_, core.vertex_count * static_cast<std::size_t>(out_count()) * sizeof(glm::vec4),
                GL_DYNAMIC_STORAGE_BIT);
  if (bounce_ == nullptr) {
    const float zero = 0.0f;
    glClearNamedBufferData(bounce_outgoing_, GL_R32F, GL_RED, GL_FLOAT, &zero);
    return;
  }
  const std::vector<glm::vec3> discs = core.object_disc_lighting(frame.settings, frame.bands);
  std::vector<glm::vec4> upload(discs.size());
  for (std::size_t i = 0; i < discs.size(); ++i) upload[i] = glm::vec4(discs[i], 0.0f);
  if (disc_lighting_ == 0)
    disc_lighting_ = make_buffer(static_cast<GLsizeiptr>(kMaxCoefficients * sizeof(glm::vec4)), nullptr, GL_DYNAMIC_STORAGE_BIT);
  glNamedBufferSubData(disc_lighting_, 0, static_cast<GLsizeiptr>(upload.size() * sizeof(glm::vec4)), upload.data());
  dispatch(core, compute_program(core, frame.bands * frame.bands, bounce_->chunks(), false), *bounce_, disc_lighting_, bounce_outgoing_);
  glDispatchCompute(static_cast<GLuint>((core.vertex_count + kWorkgroupSize - 1) / kWorkgroupSize), 1, 1);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  check_gl("computing the discs' bounce light");
}

void GlossyPass::draw(FrameCore& core, const Frame& frame) {
  if (brdf_ == 0) fail("renderer: glossy transfer " + std::to_string(frame.index) + " has no BRDF matrix (set_brdf)");
  // O = B (M L) for every vertex.
  ensure_buffer(outgoing_, outgoing_bytes_, core.vertex_count * static_cast<std::size_t>(out_count()) * sizeof(glm::vec4), 0);
  dispatch(core, compute_program(core, frame.bands * frame.bands, transfer_.chunks(), frame.sun), transfer_, core.object_lighting,
           outgoing_);
  if (frame.sun) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBounceOutgoingBinding, bounce_outgoing_);
  glDispatchCompute(static_cast<GLuint>((core.vertex_count + kWorkgroupSize - 1) / kWorkgroupSize), 1, 1);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);

  // Draw: each fragment evaluates its triangle's corners toward the eye.
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  if (frame.sun) core.sun->draw_prepass(core);
  glBindVertexArray(core.mesh_vao);
  const int out_bands = static_cast<int>(transfer_.header().bands_out);
  const Program& draw = core.program({"prt_glossy.vert", "prt_glossy.frag"},
                                     "#define OUT_BANDS " + std::to_string(out_bands) + "\n" +
                                         (frame.sun ? "#define SUN 1\n" + table_define() : std::string()));
  glUseProgram(draw.id());
  glUniformMatrix4fv(draw.uniform("model_view_projection"), 1, GL_FALSE, glm::value_ptr(core.model_view_projection));
  const glm::vec3 eye_object = core.eye_object(frame.settings);
  glUniform3f(draw.uniform("eye_object"), eye_object.x, eye_object.y, eye_object.z);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kOutgoingBinding, outgoing_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kIndicesBinding, core.indices);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPositionsBinding, core.positions);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kNormalsBinding, core.normals);
  if (vertex_brdf_ != 0) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kVertexBrdfBinding, vertex_brdf_);
  if (frame.sun) core.sun->bind(core, draw, sun_surface_, true);
  core.draw_mesh_elements();
}

}  // namespace

std::unique_ptr<TransferPass> make_glossy_pass(FrameCore& core, const PassInput& input) {
  const transfer::Header& h = input.transfer.header;
  if (input.compressed != nullptr || h.is_texel() || !transfer::is_glossy(h.kind)) return nullptr;
  check_vertex_count(core, h, input.origin);
  return std::make_unique<GlossyPass>(input);
}

}  // namespace prt::render
