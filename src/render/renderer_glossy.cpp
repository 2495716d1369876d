// The renderer's glossy PRT pass (renderer.h, PASSES: prt_glossy): BRDF matrices, the per-frame compute
// pass O = B (M L) and the draw that evaluates O toward the eye per fragment.
#include <algorithm>
#include <string>

#include <glm/gtc/type_ptr.hpp>
#include <glm/matrix.hpp>

#include "core/error.h"
#include "render/renderer.h"

namespace prt::render {

namespace {

constexpr GLuint kLightingBinding = 0;   // prt_glossy.comp: uniform Lighting (the object-frame lighting)
constexpr GLuint kBrdfBinding = 1;       // prt_glossy.comp: buffer BrdfMatrix
constexpr GLuint kOutgoingBinding = 2;   // prt_glossy.comp (written), prt_glossy.frag (read)
constexpr GLuint kIndicesBinding = 3;    // prt_glossy.frag
constexpr GLuint kPositionsBinding = 4;  // prt_glossy.frag
constexpr GLuint kNormalsBinding = 5;    // prt_glossy.frag
constexpr GLuint kWorkgroupSize = 64;    // prt_glossy.comp: local_size_x

}  // namespace

void Renderer::set_brdf(int transfer, const brdf::BrdfMatrix& matrix) {
  const transfer::Header& header = transfer_header(transfer);
  if (!transfer::is_glossy(header.kind))
    fail(std::string("renderer: set_brdf needs a glossy transfer, this one is ") + transfer::kind_name(header.kind));
  if (matrix.bands != static_cast<int>(header.bands_out))
    fail("renderer: the BRDF matrix has " + std::to_string(matrix.bands) + " bands, the transfer's output " +
         std::to_string(header.bands_out));
  if (set_compressed_brdf(transfer, matrix)) return;
  const int n = matrix.coefficients();
  std::vector<glm::vec4> entries(static_cast<std::size_t>(n) * n);
  for (int c = 0; c < 3; ++c) {
    const double* b = matrix.for_colour(c);
    for (std::size_t i = 0; i < entries.size(); ++i) entries[i][c] = static_cast<float>(b[i]);
  }
  GLuint& buffer = brdf_buffers_[static_cast<std::size_t>(transfer)];
  const auto bytes = static_cast<GLsizeiptr>(entries.size() * sizeof(glm::vec4));
  if (buffer != 0 && brdf_bands_[static_cast<std::size_t>(transfer)] == matrix.bands) {
    glNamedBufferSubData(buffer, 0, bytes, entries.data());
  } else {
    if (buffer != 0) glDeleteBuffers(1, &buffer);
    glCreateBuffers(1, &buffer);
    glNamedBufferStorage(buffer, bytes, entries.data(), GL_DYNAMIC_STORAGE_BIT);
  }
  brdf_bands_[static_cast<std::size_t>(transfer)] = matrix.bands;
  check_gl("uploading a BRDF matrix");
}

void Renderer::draw_glossy(const FrameSettings& settings, int bands, bool sun) {
  const TransferBuffer& transfer = *transfers_[static_cast<std::size_t>(settings.transfer)];
  const transfer::Header& header = transfer.header();
  const GLuint brdf = brdf_buffers_[static_cast<std::size_t>(settings.transfer)];
  if (brdf == 0) fail("renderer: glossy transfer " + std::to_string(settings.transfer) + " has no BRDF matrix (set_brdf)");
  const int out_bands = static_cast<int>(header.bands_out), out_count = out_bands * out_bands;

  // O = B (M L) for every vertex.
  const std::size_t bytes = vertex_count_ * static_cast<std::size_t>(out_count) * sizeof(glm::vec4);
  if (outgoing_ == 0 || outgoing_bytes_ < bytes) {
    if (outgoing_ != 0) glDeleteBuffers(1, &outgoing_);
    glCreateBuffers(1, &outgoing_);
    glNamedBufferStorage(outgoing_, static_cast<GLsizeiptr>(std::max<std::size_t>(bytes, 16)), nullptr, 0);
    outgoing_bytes_ = bytes;
  }
  const Program& compute = glossy_compute_program(static_cast<int>(header.channels), static_cast<int>(header.bands * header.bands),
                                                  bands * bands, out_count, transfer.chunks(), sun);
  glUseProgram(compute.id());
  transfer.bind();
  glUniform1i(compute.uniform("vertices_per_chunk"), static_cast<GLint>(transfer.vertices_per_chunk()));
  glUniform1i(compute.uniform("vertex_count"), static_cast<GLint>(vertex_count_));
  glBindBufferBase(GL_UNIFORM_BUFFER, kLightingBinding, object_lighting_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBrdfBinding, brdf);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kOutgoingBinding, outgoing_);
  if (sun) bind_sun_bounce();
  glDispatchCompute(static_cast<GLuint>((vertex_count_ + kWorkgroupSize - 1) / kWorkgroupSize), 1, 1);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);

  // Draw: each fragment evaluates its triangle's corners toward the eye.
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  if (sun) draw_sun_prepass();
  glBindVertexArray(mesh_vao_);
  const Program& draw = glossy_draw_program(out_bands, sun);
  glUseProgram(draw.id());
  glUniformMatrix4fv(draw.uniform("model_view_projection"), 1, GL_FALSE, glm::value_ptr(model_view_projection_));
  // The eye in mesh coordinates: world = c + R_object (p - c), so p = c + R_object^T (eye - c).
  const glm::dvec3 eye_object = view_.centre + glm::transpose(settings.object_rotation) * (view_.eye - view_.centre);
  glUniform3f(draw.uniform("eye_object"), static_cast<float>(eye_object.x), static_cast<float>(eye_object.y),
              static_cast<float>(eye_object.z));
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kOutgoingBinding, outgoing_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kIndicesBinding, indices_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPositionsBinding, positions_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kNormalsBinding, normals_);
  if (sun) bind_sun(draw, settings, true);
  glDrawElements(GL_TRIANGLES, index_count_, GL_UNSIGNED_INT, nullptr);
}

const Program& Renderer::glossy_compute_program(int channels, int in_count, int used_count, int out_count, int chunks,
                                                bool sun) {
  const auto key = std::make_tuple(channels, in_count, used_count, out_count, chunks, sun);
  auto found = glossy_compute_programs_.find(key);
  if (found == glossy_compute_programs_.end()) {
    const std::string defines = "#define CHANNELS " + std::to_string(channels) + "\n#define IN_COUNT " + std::to_string(in_count) +
                                "\n#define USED_COUNT " + std::to_string(used_count) + "\n#define OUT_COUNT " +
                                std::to_string(out_count) + "\n#define CHUNKS " + std::to_string(chunks) + "\n" +
                                (sun ? "#define SUN 1\n" : "");
    found = glossy_compute_programs_.emplace(key, Program({"prt_glossy.comp"}, defines)).first;
  }
  return found->second;
}

const Program& Renderer::glossy_draw_program(int out_bands, bool sun) {
  const auto key = std::make_pair(out_bands, sun);
  auto found = glossy_draw_programs_.find(key);
  if (found == glossy_draw_programs_.end())
    found = glossy_draw_programs_
                .emplace(key, Program({"prt_glossy.vert", "prt_glossy.frag"},
                                      "#define OUT_BANDS " + std::to_string(out_bands) + "\n" + (sun ? "#define SUN 1\n" : "")))
                .first;
  return found->second;
}

}  // namespace prt::render
