#include "render/renderer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numeric>

#include <glm/geometric.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/mat3x3.hpp>

#include "compress/compressed.h"
#include "core/error.h"
#include "render/frame_core.h"
#include "render/transfer_pass.h"
#include "shade/shade.h"

namespace prt::render {

namespace {

std::string mebibytes(std::uint64_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f MiB", static_cast<double>(bytes) / (1024.0 * 1024.0));
  return text;
}

}  // namespace

Background parse_background(const std::string& name) {
  if (name == "black") return Background::black;
  if (name == "env") return Background::environment;
  if (name == "sh") return Background::sh;
  fail_option("background", ": expected env, sh or black, got '" + name + "'");
}

const char* background_name(Background background) {
  switch (background) {
    case Background::black: return "black";
    case Background::environment: return "env";
    case Background::sh: return "sh";
  }
  return "?";
}

int used_bands(const transfer::Header& header, int requested) { return shade::shading_bands(header, requested); }

void lambert_light(const sh::RgbCoefficients& lighting, glm::dvec3& direction, glm::dvec3& radiance) {
  const glm::dvec3 luminance_weights(0.2126, 0.7152, 0.0722);
  radiance = lighting.values.empty() ? glm::dvec3(0.0) : lighting.values[0] * 0.28209479177387814;
  direction = glm::dvec3(0.0, 1.0, 0.0);
  if (lighting.bands < 2) return;
  // Band 1 is (-c y, c z, -c x): the linear part of the lighting grows fastest along (-L3, -L1, L2).
  const glm::dvec3 axis(-glm::dot(lighting.values[3], luminance_weights),
                        -glm::dot(lighting.values[1], luminance_weights),
                        glm::dot(lighting.values[2], luminance_weights));
  const double length = glm::length(axis);
  if (length > 0.0) direction = axis / length;
}

// ---------------------------------------------------------------------------------------------------
TransferBuffer::TransferBuffer(const transfer::TransferData& transfer, const std::string& origin,
                               std::size_t max_range_bytes)
    : header_(transfer.header) {
  if (transfer.values.size() != header_.vertex_count * header_.values_per_vertex())
    fail_file(origin, "transfer value count does not match its header");
  GLint64 max_texels = 0, alignment = 0;
  glGetInteger64v(GL_MAX_TEXTURE_BUFFER_SIZE, &max_texels);
  glGetInteger64v(GL_TEXTURE_BUFFER_OFFSET_ALIGNMENT, &alignment);
  std::uint64_t limit = static_cast<std::uint64_t>(std::max<GLint64>(max_texels, 1)) * sizeof(float);
  if (max_range_bytes > 0) limit = std::min<std::uint64_t>(limit, max_range_bytes);
  const std::uint64_t vertex_bytes = header_.values_per_vertex() * sizeof(float);
  const std::uint64_t bytes = header_.vertex_count * vertex_bytes;

  // Whole vertices per view, a multiple of the step that keeps every view's offset aligned.
  const std::uint64_t align = static_cast<std::uint64_t>(std::max<GLint64>(alignment, 1));
  const std::uint64_t step = align / std::gcd(vertex_bytes, align);
  std::uint64_t per_chunk = limit / vertex_bytes;
  per_chunk -= per_chunk % step;
  const std::uint64_t chunks = per_chunk == 0 ? 0 : (header_.vertex_count + per_chunk - 1) / per_chunk;
  if (per_chunk == 0 || chunks > static_cast<std::uint64_t>(kMaxTransferChunks))
    fail_file(origin, "transfer is " + mebibytes(bytes) + "; the renderer reads at most " +
                          std::to_string(kMaxTransferChunks) + " buffer textures of " + mebibytes(limit) +
                          " on this OpenGL; use fewer bands or a smaller mesh");
  chunks_ = std::max(1, static_cast<int>(chunks));
  // The shader divides a 32-bit vertex index by this, so it is capped at INT32_MAX.
  vertices_per_chunk_ = static_cast<std::size_t>(std::clamp<std::uint64_t>(per_chunk, 1, 0x7fffffff));

  // One copy into immutable storage. (On llvmpipe the driver's zero-filled allocation dominates: fresh
  // pages cost more than the copy; see bench_render.)
  buffer_ = make_buffer(static_cast<GLsizeiptr>(bytes), transfer.values.data(), 0);
  views_.resize(static_cast<std::size_t>(chunks_));
  glCreateTextures(GL_TEXTURE_BUFFER, chunks_, views_.data());
  for (int k = 0; k < chunks_; ++k) {
    const std::uint64_t first = static_cast<std::uint64_t>(k) * vertices_per_chunk_;
    const std::uint64_t count = std::min<std::uint64_t>(vertices_per_chunk_, header_.vertex_count - std::min(first, header_.vertex_count));
    glTextureBufferRange(views_[static_cast<std::size_t>(k)], GL_R32F, buffer_, static_cast<GLintptr>(first * vertex_bytes),
                         static_cast<GLsizeiptr>(std::max<std::uint64_t>(count * vertex_bytes, 4)));
  }
  check_gl("uploading transfer");
}

void TransferBuffer::bind() const {
  for (int k = 0; k < chunks_; ++k) glBindTextureUnit(static_cast<GLuint>(k), views_[static_cast<std::size_t>(k)]);
}

TransferBuffer::~TransferBuffer() {
  if (!views_.empty()) glDeleteTextures(static_cast<GLsizei>(views_.size()), views_.data());
  delete_buffer(buffer_);
}

// ---------------------------------------------------------------------------------------------------
Renderer::Renderer() : core_(std::make_unique<FrameCore>()) {
  diffuse_program(*core_, 3, 25, 25, 1, false);  // compile errors in prt_diffuse.vert surface here, not at the first frame
}

Renderer::~Renderer() {
  passes_.clear();
  core_.reset();
}

void Renderer::set_mesh(const mesh::Mesh& mesh) {
  passes_.clear();
  core_->set_mesh(mesh);
}

int Renderer::add(const transfer::TransferData& transfer, const compress::CompressedTransfer* compressed, const std::string& origin,
                  std::size_t max_range_bytes) {
  passes_.push_back(make_pass(*core_, PassInput{transfer, compressed, origin, max_range_bytes}));
  return static_cast<int>(passes_.size()) - 1;
}

int Renderer::add_transfer(const transfer::TransferData& transfer, const std::string& origin, std::size_t max_range_bytes) {
  return add(transfer, nullptr, origin, max_range_bytes);
}

int Renderer::add_compressed(const compress::CompressedTransfer& compressed, const std::string& origin) {
  transfer::TransferData header_only;
  header_only.header = compressed.source;
  header_only.header.scalar = transfer::Scalar::float32;
  return add(header_only, &compressed, origin);
}

int Renderer::add_mixed(int texel, int vertex, const TriangleRuns& vertex_runs) {
  passes_.push_back(make_mixed_pass(*core_, pass(texel), pass(vertex), vertex_runs));
  return static_cast<int>(passes_.size()) - 1;
}

int Renderer::add_lightmap(const transfer::TransferData& transfer, const std::string& origin) {
  if (!transfer.header.is_texel()) fail_file(origin, "not a texel (lightmap) transfer");
  return add(transfer, nullptr, origin);
}

TransferPass& Renderer::pass(int index) const {
  if (index < 0 || index >= transfer_count()) fail("renderer: no transfer " + std::to_string(index));
  return *passes_[static_cast<std::size_t>(index)];
}

const transfer::Header& Renderer::transfer_header(int index) const { return pass(index).header(); }

bool Renderer::is_compressed(int index) const {
  return index >= 0 && index < transfer_count() && std::strcmp(pass(index).name(), "cpca") == 0;
}

bool Renderer::is_lightmap(int index) const {
  // "lightmap", or "lightmap_cpca" (a compressed lightmap, drawn compressed)
  return index >= 0 && index < transfer_count() && std::strncmp(pass(index).name(), "lightmap", 8) == 0;
}

void Renderer::set_brdf(int transfer, const brdf::BrdfMatrix& matrix) {
  const transfer::Header& header = transfer_header(transfer);
  if (!transfer::is_glossy(header.kind))
    fail(std::string("renderer: set_brdf needs a glossy transfer, this one is ") + transfer::kind_name(header.kind));
  if (matrix.bands != static_cast<int>(header.bands_out))
    fail("renderer: the BRDF matrix has " + std::to_string(matrix.bands) + " bands, the transfer's output " +
         std::to_string(header.bands_out));
  pass(transfer).set_brdf(matrix);
}

void Renderer::set_brdf(int transfer, const brdf::BrdfMatrix& matrix, const brdf::Brdf& surface) {
  const std::vector<brdf::Term> terms = brdf::terms(surface);
  if (terms.size() > static_cast<std::size_t>(kMaxBrdfTerms))
    fail("renderer: the BRDF has " + std::to_string(terms.size()) + " terms; the disc term evaluates at most " +
         std::to_string(kMaxBrdfTerms));
  set_brdf(transfer, matrix);
  SunSurface& sun = pass(transfer).sun_surface();
  sun.terms = terms;
  sun.has_terms = true;
}

void Renderer::set_brdfs(int transfer, const brdf::VertexBrdfs& brdfs) {
  const transfer::Header& header = transfer_header(transfer);
  if (!transfer::is_glossy(header.kind))
    fail(std::string("renderer: set_brdfs needs a glossy transfer, this one is ") + transfer::kind_name(header.kind));
  if (brdfs.table.empty()) fail("renderer: set_brdfs needs at least one BRDF");
  if (brdfs.table.size() == 1) {
    set_brdf(transfer, brdf::project(brdfs.table[0], static_cast<int>(header.bands_out)), brdfs.table[0]);
    return;
  }
  if (brdfs.vertex.size() != core_->vertex_count)
    fail("renderer: set_brdfs has " + std::to_string(brdfs.vertex.size()) + " vertex indices for " +
         std::to_string(core_->vertex_count) + " vertices");
  for (std::uint32_t index : brdfs.vertex)
    if (index >= brdfs.table.size())
      fail("renderer: a vertex's BRDF index " + std::to_string(index) + " is not below the table's " +
           std::to_string(brdfs.table.size()) + " BRDFs");
  std::vector<brdf::BrdfMatrix> matrices;
  std::vector<glm::vec4> terms(brdfs.table.size() * 2 * kMaxBrdfTerms, glm::vec4(0.0f));  // sun_light.glsl BrdfTerms
  for (std::size_t b = 0; b < brdfs.table.size(); ++b) {
    matrices.push_back(brdf::project(brdfs.table[b], static_cast<int>(header.bands_out)));
    const std::vector<brdf::Term> t = brdf::terms(brdfs.table[b]);
    if (t.size() > static_cast<std::size_t>(kMaxBrdfTerms))
      fail("renderer: BRDF " + std::to_string(b) + " has " + std::to_string(t.size()) +
           " terms; the disc term evaluates at most " + std::to_string(kMaxBrdfTerms));
    for (std::size_t i = 0; i < t.size(); ++i) {
      const std::size_t at = 2 * (b * kMaxBrdfTerms + i);
      terms[at] = glm::vec4(static_cast<float>(static_cast<int>(t[i].shape)), static_cast<float>(t[i].parameter),
                            i == 0 ? static_cast<float>(t.size()) : 0.0f, 0.0f);
      terms[at + 1] = glm::vec4(glm::vec3(t[i].weight), 0.0f);
    }
  }
  pass(transfer).set_brdf_table(matrices, brdfs.vertex);
  SunSurface& sun = pass(transfer).sun_surface();
  delete_buffer(sun.term_table);
  sun.term_table = make_buffer(static_cast<GLsizeiptr>(terms.size() * sizeof(glm::vec4)), terms.data(), 0);
  sun.terms = brdf::terms(brdfs.table[0]);
  sun.has_terms = true;
  check_gl("uploading the BRDFs' terms");
}

void Renderer::set_surface_albedo(int transfer, const std::vector<glm::vec3>& albedo) {
  TransferPass& p = pass(transfer);
  if (albedo.size() != core_->vertex_count)
    fail("renderer: surface albedo has " + std::to_string(albedo.size()) + " entries for " + std::to_string(core_->vertex_count) +
         " vertices");
  p.set_surface_albedo(albedo);
}

void Renderer::set_textured(int transfer, bool textured) {
  TransferPass& p = pass(transfer);
  if (textured && !core_->base_colour.present()) fail("renderer: set_textured: the mesh has no texture");
  p.set_textured(textured);
}

void Renderer::set_lighting(const sh::RgbCoefficients& lighting, const image::Image* equirect) { core_->set_lighting(lighting, equirect); }
bool Renderer::has_environment_image() const { return core_->environment_texture != 0; }
void Renderer::set_discs(const std::vector<light::Disc>& discs) { core_->sun->set_discs(discs); }
int Renderer::disc_count() const { return static_cast<int>(core_->sun->discs().size()); }
int Renderer::shadow_map_updates() const { return core_->sun->updates(); }
const ViewMatrices& Renderer::last_view() const { return core_->view; }
const glm::mat4& Renderer::last_model_view_projection() const { return core_->model_view_projection; }
int Renderer::width() const { return core_->width; }
int Renderer::height() const { return core_->height; }

void Renderer::update_lighting(const glm::dmat3& environment_rotation, const glm::dmat3& object_rotation, int bands) {
  core_->update_lighting(environment_rotation, object_rotation, bands);
}

std::vector<float> Renderer::shadow_visibility(const FrameSettings& settings, int disc) {
  if (!core_->has_mesh) fail("renderer: no mesh");
  if (disc < 0 || disc >= disc_count()) fail("renderer: no disc " + std::to_string(disc));
  transfer_header(settings.transfer);
  core_->sun->update_maps(*core_, glm::transpose(settings.object_rotation) * settings.environment_rotation);
  return core_->sun->visibility(*core_, disc);
}

void Renderer::prepare(TransferPass& p, const Frame& frame) {
  core_->update_lighting(frame.settings.environment_rotation, frame.settings.object_rotation, frame.bands);
  if (!frame.sun) return;  // before the frame's framebuffer is bound:
  core_->sun->update_maps(*core_, glm::transpose(frame.settings.object_rotation) * frame.settings.environment_rotation);
  p.prepare_sun(*core_, frame);
}

void Renderer::render(const FrameSettings& settings, int width, int height) {
  FrameCore& core = *core_;
  if (!core.has_mesh) fail("renderer: no mesh");
  const bool prt = settings.shading == Shading::prt;
  TransferPass* p = prt ? &pass(settings.transfer) : nullptr;
  const int bands = prt ? used_bands(p->header(), settings.bands)
                        : settings.bands > 0 ? std::min(settings.bands, core.lighting_bands) : core.lighting_bands;
  if (settings.background == Background::environment && core.environment_texture == 0)
    fail_option("background", " env: the lighting has no environment image (an SH lighting file); use sh or black");

  core.resize(width, height);
  core.set_view(settings.camera, settings.object_rotation, width, height);
  const Frame frame{settings, settings.transfer, bands, prt && settings.sun && disc_count() > 0, false};
  if (prt) prepare(*p, frame);
  core.begin_frame(true);
  core.draw_background(settings, bands);
  if (prt)
    p->draw(core, frame);
  else
    core.draw_lambert(settings);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  check_gl("rendering a frame");
}

void Renderer::render_texels(const FrameSettings& settings) {
  FrameCore& core = *core_;
  if (!core.has_mesh) fail("renderer: no mesh");
  if (!is_lightmap(settings.transfer)) fail("renderer: transfer " + std::to_string(settings.transfer) + " is not a lightmap");
  TransferPass& p = pass(settings.transfer);
  const int bands = used_bands(p.header(), settings.bands);
  const int width = static_cast<int>(p.header().texel_width), height = static_cast<int>(p.header().texel_height);
  core.resize(width, height);
  core.set_view(settings.camera, settings.object_rotation, width, height);
  const Frame frame{settings, settings.transfer, bands, settings.sun && settings.shading == Shading::prt && disc_count() > 0, true};
  prepare(p, frame);
  core.begin_frame(false);
  p.draw(core, frame);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  check_gl("rendering lightmap texels");
}

image::Image Renderer::read_radiance() const {
  const FrameCore& core = *core_;
  image::Image out(core.width, core.height, 3);
  if (core.framebuffer == 0) return out;
  std::vector<float> rgba(static_cast<std::size_t>(core.width) * core.height * 4);
  glNamedFramebufferReadBuffer(core.framebuffer, GL_COLOR_ATTACHMENT0);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, core.framebuffer);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glReadPixels(0, 0, core.width, core.height, GL_RGBA, GL_FLOAT, rgba.data());
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  check_gl("reading radiance");
  // GL rows go up from the bottom; image rows go down from the top.
  for (int y = 0; y < core.height; ++y) {
    const float* row = rgba.data() + static_cast<std::size_t>(core.height - 1 - y) * core.width * 4;
    for (int x = 0; x < core.width; ++x)
      for (int c = 0; c < 3; ++c) out.at(x, y, c) = row[static_cast<std::size_t>(x) * 4 + c];
  }
  return out;
}

std::vector<std::uint32_t> Renderer::read_triangle_ids() const {
  const FrameCore& core = *core_;
  const int width = core.width, height = core.height;
  std::vector<std::uint32_t> gl_rows(static_cast<std::size_t>(width) * height);
  if (core.framebuffer == 0) return gl_rows;
  glNamedFramebufferReadBuffer(core.framebuffer, GL_COLOR_ATTACHMENT1);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, core.framebuffer);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glReadPixels(0, 0, width, height, GL_RED_INTEGER, GL_UNSIGNED_INT, gl_rows.data());
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  check_gl("reading triangle ids");
  std::vector<std::uint32_t> out(gl_rows.size());
  for (int y = 0; y < height; ++y)
    std::memcpy(out.data() + static_cast<std::size_t>(y) * width, gl_rows.data() + static_cast<std::size_t>(height - 1 - y) * width,
                sizeof(std::uint32_t) * width);
  return out;
}

void Renderer::present(GLuint target, double exposure_stops, image::ToneMap tone_map) {
  const FrameCore& core = *core_;
  if (core.framebuffer == 0) return;
  glBindFramebuffer(GL_FRAMEBUFFER, target);
  glViewport(0, 0, core.width, core.height);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_FRAMEBUFFER_SRGB);  // the shader encodes sRGB itself, as to_display does
  glUseProgram(core.tonemap.id());
  glBindVertexArray(core.empty_vao);
  glBindTextureUnit(0, core.radiance_texture);
  glUniform1f(core.tonemap.uniform("exposure_scale"), static_cast<float>(std::exp2(exposure_stops)));
  glUniform1i(core.tonemap.uniform("tone_map"), tone_map == image::ToneMap::aces ? 1 : 0);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  check_gl("presenting a frame");
}

}  // namespace prt::render
