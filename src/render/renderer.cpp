#include "render/renderer.h"
#include "render/renderer_cpca.h"
#include "render/renderer_lightmap.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numeric>

#include <glm/geometric.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/mat3x3.hpp>

#include "core/error.h"
#include "render/renderer_sun.h"
#include "sh/basis.h"
#include "sh/rotation.h"

namespace prt::render {

namespace {

constexpr int kMaxCoefficients = sh::kMaxBands * sh::kMaxBands;
constexpr GLsizeiptr kLightingBytes = kMaxCoefficients * static_cast<GLsizeiptr>(sizeof(glm::vec4));
constexpr GLuint kObjectLightingBinding = 0;       // prt_diffuse.vert: uniform Lighting
constexpr GLuint kEnvironmentLightingBinding = 1;  // background.frag: uniform EnvironmentLighting
constexpr float kDefaultAlbedo = 0.8f;

GLuint make_buffer(GLsizeiptr bytes, const void* data, GLbitfield flags) {
  GLuint buffer = 0;
  glCreateBuffers(1, &buffer);
  glNamedBufferStorage(buffer, std::max<GLsizeiptr>(bytes, 4), data, flags);
  return buffer;
}

glm::mat3 to_float(const glm::dmat3& m) { return glm::mat3(m); }

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
Renderer::Renderer()
    : background_({"fullscreen.vert", "background.frag"}),
      background_discs_({"fullscreen.vert", "background.frag"}, "#define DISCS 1\n"),
      lambert_({"lambert.vert", "surface.frag"}),
      tonemap_({"fullscreen.vert", "tonemap.frag"}),
      lighting_(kMaxCoefficients, glm::vec3(0.0f)),
      rotated_(kMaxCoefficients, glm::vec3(0.0f)),
      upload_(kMaxCoefficients, glm::vec4(0.0f)) {
  prt_program(3, 25, 25, 1);  // compile errors in prt_diffuse.vert surface here, not at the first frame
  sun_ = std::make_unique<SunPass>();
  lightmap_ = std::make_unique<LightmapPass>();
  glCreateVertexArrays(1, &empty_vao_);
  object_lighting_ = make_buffer(kLightingBytes, upload_.data(), GL_DYNAMIC_STORAGE_BIT);
  environment_lighting_ = make_buffer(kLightingBytes, upload_.data(), GL_DYNAMIC_STORAGE_BIT);
  check_gl("creating renderer");
}

Renderer::~Renderer() {
  sun_.reset();
  lightmap_.reset();
  transfers_.clear();
  compressed_.clear();
  for (GLuint& buffer : brdf_buffers_) delete_buffer(buffer);
  delete_buffer(outgoing_);
  delete_buffer(positions_);
  delete_buffer(normals_);
  delete_buffer(albedo_);
  delete_buffer(indices_);
  delete_buffer(object_lighting_);
  delete_buffer(environment_lighting_);
  delete_texture(environment_texture_);
  delete_texture(radiance_texture_);
  delete_texture(triangle_texture_);
  if (depth_buffer_ != 0) glDeleteRenderbuffers(1, &depth_buffer_);
  if (framebuffer_ != 0) glDeleteFramebuffers(1, &framebuffer_);
  if (mesh_vao_ != 0) glDeleteVertexArrays(1, &mesh_vao_);
  if (empty_vao_ != 0) glDeleteVertexArrays(1, &empty_vao_);
}

void Renderer::set_mesh(const mesh::Mesh& mesh) {
  sun_->clear_mesh();
  lightmap_->set_mesh(mesh);
  transfers_.clear();
  compressed_.clear();
  for (GLuint& buffer : brdf_buffers_) delete_buffer(buffer);
  brdf_buffers_.clear();
  brdf_bands_.clear();
  delete_buffer(positions_);
  delete_buffer(normals_);
  delete_buffer(albedo_);
  delete_buffer(indices_);
  if (mesh_vao_ != 0) glDeleteVertexArrays(1, &mesh_vao_);

  const auto vec3_bytes = static_cast<GLsizeiptr>(mesh.positions.size() * sizeof(glm::vec3));
  positions_ = make_buffer(vec3_bytes, mesh.positions.data(), 0);
  normals_ = make_buffer(vec3_bytes, mesh.normals.data(), 0);
  if (mesh.albedo.size() == mesh.positions.size()) {
    albedo_ = make_buffer(vec3_bytes, mesh.albedo.data(), 0);
  } else {
    const std::vector<glm::vec3> grey(mesh.positions.size(), glm::vec3(kDefaultAlbedo));
    albedo_ = make_buffer(vec3_bytes, grey.data(), 0);
  }
  indices_ = make_buffer(static_cast<GLsizeiptr>(mesh.indices.size() * sizeof(std::uint32_t)), mesh.indices.data(), 0);

  glCreateVertexArrays(1, &mesh_vao_);
  const GLuint sources[3] = {positions_, normals_, albedo_};
  for (GLuint location = 0; location < 3; ++location) {
    glVertexArrayVertexBuffer(mesh_vao_, location, sources[location], 0, sizeof(glm::vec3));
    glVertexArrayAttribFormat(mesh_vao_, location, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(mesh_vao_, location, location);
    glEnableVertexArrayAttrib(mesh_vao_, location);
  }
  glVertexArrayElementBuffer(mesh_vao_, indices_);
  check_gl("uploading mesh");

  index_count_ = static_cast<GLsizei>(mesh.indices.size());
  vertex_count_ = mesh.vertex_count();
  bounds_ = mesh::bounds(mesh);
  has_mesh_ = true;
}

int Renderer::add_transfer(const transfer::TransferData& transfer, const std::string& origin,
                           std::size_t max_range_bytes) {
  if (!has_mesh_) fail("renderer: set a mesh before its transfer");
  if (transfer.header.vertex_count != vertex_count_)
    fail_file(origin, "transfer has " + std::to_string(transfer.header.vertex_count) + " vertices, the mesh " +
                          std::to_string(vertex_count_));
  transfers_.push_back(std::make_unique<TransferBuffer>(transfer, origin, max_range_bytes));
  sun_->add_transfer(transfer, origin, max_range_bytes);
  brdf_buffers_.push_back(0);
  brdf_bands_.push_back(0);
  return static_cast<int>(transfers_.size()) - 1;
}

const transfer::Header& Renderer::transfer_header(int index) const {
  if (index < 0 || index >= transfer_count()) fail("renderer: no transfer " + std::to_string(index));
  if (is_compressed(index)) return compressed_[static_cast<std::size_t>(index)]->header();
  if (is_lightmap(index)) return lightmap_header(index);
  return transfers_[static_cast<std::size_t>(index)]->header();
}

void Renderer::set_lighting(const sh::RgbCoefficients& lighting, const image::Image* equirect) {
  std::fill(lighting_.begin(), lighting_.end(), glm::vec3(0.0f));
  const std::size_t count = std::min<std::size_t>(lighting.values.size(), kMaxCoefficients);
  for (std::size_t i = 0; i < count; ++i) lighting_[i] = glm::vec3(lighting.values[i]);
  lighting_bands_ = std::max(1, std::min(lighting.bands, sh::kMaxBands));
  for (std::size_t i = 0; i < kMaxCoefficients; ++i) upload_[i] = glm::vec4(lighting_[i], 0.0f);
  glNamedBufferSubData(environment_lighting_, 0, kLightingBytes, upload_.data());
  lambert_light(lighting, lambert_direction_, lambert_radiance_);

  delete_texture(environment_texture_);
  if (equirect != nullptr) {
    if (equirect->channels != 3 || equirect->width < 1 || equirect->height < 1)
      fail("renderer: the environment image must be RGB and not empty");
    glCreateTextures(GL_TEXTURE_2D, 1, &environment_texture_);
    glTextureStorage2D(environment_texture_, 1, GL_RGB32F, equirect->width, equirect->height);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    // Row 0 of the image (the top, v = 0, +Y) goes to texture row t = 0: the shader samples at t = v.
    glTextureSubImage2D(environment_texture_, 0, 0, 0, equirect->width, equirect->height, GL_RGB, GL_FLOAT,
                        equirect->pixels.data());
    glTextureParameteri(environment_texture_, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(environment_texture_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(environment_texture_, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(environment_texture_, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  }
  check_gl("uploading lighting");
}

void Renderer::update_lighting(const glm::dmat3& environment_rotation, const glm::dmat3& object_rotation,
                               int bands) {
  // Lighting seen in the object's frame: rotate by the environment's rotation, then undo the object's.
  const glm::mat3 rotation = to_float(glm::transpose(object_rotation) * environment_rotation);
  sh::rotate_rgb(bands, rotation, lighting_.data(), rotated_.data());
  const int count = bands * bands;
  for (int i = 0; i < count; ++i) upload_[static_cast<std::size_t>(i)] = glm::vec4(rotated_[static_cast<std::size_t>(i)], 0.0f);
  glNamedBufferSubData(object_lighting_, 0, static_cast<GLsizeiptr>(count * sizeof(glm::vec4)), upload_.data());
}

void Renderer::resize(int width, int height) {
  if (width == width_ && height == height_ && framebuffer_ != 0) return;
  delete_texture(radiance_texture_);
  delete_texture(triangle_texture_);
  if (depth_buffer_ != 0) glDeleteRenderbuffers(1, &depth_buffer_);
  if (framebuffer_ != 0) glDeleteFramebuffers(1, &framebuffer_);

  glCreateTextures(GL_TEXTURE_2D, 1, &radiance_texture_);
  glTextureStorage2D(radiance_texture_, 1, GL_RGBA32F, width, height);
  glCreateTextures(GL_TEXTURE_2D, 1, &triangle_texture_);
  glTextureStorage2D(triangle_texture_, 1, GL_R32UI, width, height);
  for (GLuint texture : {radiance_texture_, triangle_texture_}) {
    glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  }
  glCreateRenderbuffers(1, &depth_buffer_);
  glNamedRenderbufferStorage(depth_buffer_, GL_DEPTH_COMPONENT32F, width, height);
  glCreateFramebuffers(1, &framebuffer_);
  glNamedFramebufferTexture(framebuffer_, GL_COLOR_ATTACHMENT0, radiance_texture_, 0);
  glNamedFramebufferTexture(framebuffer_, GL_COLOR_ATTACHMENT1, triangle_texture_, 0);
  glNamedFramebufferRenderbuffer(framebuffer_, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_buffer_);
  const GLenum draw_buffers[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  glNamedFramebufferDrawBuffers(framebuffer_, 2, draw_buffers);
  if (glCheckNamedFramebufferStatus(framebuffer_, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    fail("renderer: cannot create a " + std::to_string(width) + "x" + std::to_string(height) +
         " float framebuffer");
  check_gl("creating framebuffer");
  width_ = width;
  height_ = height;
}

void Renderer::render(const FrameSettings& settings, int width, int height) {
  if (!has_mesh_) fail("renderer: no mesh");
  const bool prt = settings.shading == Shading::prt;
  int bands = 0;
  if (prt) {
    const transfer::Header& header = transfer_header(settings.transfer);
    const int transfer_bands = static_cast<int>(header.bands);
    if (settings.bands < 0 || settings.bands > transfer_bands)
      fail_option("bands", ": must be between 1 and the transfer's " + std::to_string(transfer_bands) + " bands, got " +
           std::to_string(settings.bands));
    bands = settings.bands == 0 ? transfer_bands : settings.bands;
  } else {
    bands = settings.bands > 0 ? std::min(settings.bands, lighting_bands_) : lighting_bands_;
  }
  if (settings.background == Background::environment && environment_texture_ == 0)
    fail_option("background", " env: the lighting has no environment image (an SH lighting file); use sh or black");

  resize(width, height);
  view_ = orbit_view(settings.camera, bounds_, width, height, settings.object_rotation);
  model_view_projection_ = glm::mat4(view_.projection * view_.view * view_.model);
  if (prt) update_lighting(settings.environment_rotation, settings.object_rotation, bands);
  const bool sun = sun_active(settings);
  if (sun) update_sun(settings, bands);  // before the frame's framebuffer is bound

  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  glViewport(0, 0, width, height);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_FRAMEBUFFER_SRGB);
  glDepthMask(GL_TRUE);
  const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  const GLuint none[4] = {kNoTriangle, 0, 0, 0};
  const float far_depth = 1.0f;
  glClearNamedFramebufferfv(framebuffer_, GL_COLOR, 0, zero);
  glClearNamedFramebufferuiv(framebuffer_, GL_COLOR, 1, none);
  glClearNamedFramebufferfv(framebuffer_, GL_DEPTH, 0, &far_depth);

  draw_background(settings, bands);
  if (prt && is_compressed(settings.transfer))
    draw_cpca(settings, bands, sun);
  else if (prt && is_lightmap(settings.transfer))
    draw_lightmap(settings, bands, sun, false);
  else if (prt && transfer::is_glossy(transfer_header(settings.transfer).kind))
    draw_glossy(settings, bands, sun);
  else
    draw_mesh(settings, bands, sun);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  check_gl("rendering a frame");
}

void Renderer::draw_background(const FrameSettings& settings, int bands) {
  if (settings.background == Background::black) return;  // the clear colour is black
  glDisable(GL_DEPTH_TEST);
  draw_background_pass(background_, settings, bands);
  if (!settings.sun || disc_count() == 0) return;
  // The sky again with the discs, over each disc's rectangle only (the disc program costs per pixel).
  glEnable(GL_SCISSOR_TEST);
  for (const light::Disc& disc : sun_->discs) {
    const auto rect = camera::cap_pixel_rect(view_, width_, height_, settings.environment_rotation * disc.direction,
                                             disc.angular_radius);
    if (!rect) continue;
    glScissor(rect->x0, rect->y0, rect->x1 - rect->x0, rect->y1 - rect->y0);
    draw_background_pass(background_discs_, settings, bands);
  }
  glDisable(GL_SCISSOR_TEST);
}

void Renderer::draw_background_pass(const Program& program, const FrameSettings& settings, int bands) {
  glUseProgram(program.id());
  glBindVertexArray(empty_vao_);
  glBindBufferBase(GL_UNIFORM_BUFFER, kEnvironmentLightingBinding, environment_lighting_);
  if (environment_texture_ != 0) glBindTextureUnit(0, environment_texture_);
  const glm::mat3 camera_to_world = to_float(view_.camera_to_world);
  const glm::mat3 world_to_environment = to_float(glm::transpose(settings.environment_rotation));
  glUniformMatrix3fv(program.uniform("camera_to_world"), 1, GL_FALSE, glm::value_ptr(camera_to_world));
  glUniformMatrix3fv(program.uniform("world_to_environment"), 1, GL_FALSE, glm::value_ptr(world_to_environment));
  glUniform2f(program.uniform("tan_half_fov"), static_cast<float>(view_.tan_half_fov_x),
              static_cast<float>(view_.tan_half_fov_y));
  glUniform1i(program.uniform("mode"), settings.background == Background::environment ? 1 : 2);
  glUniform1i(program.uniform("sh_bands"), bands);
  if (&program == &background_discs_) bind_background_discs();
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

void Renderer::draw_mesh(const FrameSettings& settings, int bands, bool sun) {
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glBindVertexArray(mesh_vao_);
  const bool prt = settings.shading == Shading::prt;
  const TransferBuffer* transfer = prt ? transfers_[static_cast<std::size_t>(settings.transfer)].get() : nullptr;
  const Program& program =
      prt ? prt_program(static_cast<int>(transfer->header().channels),
                        static_cast<int>(transfer->header().bands * transfer->header().bands), bands * bands,
                        transfer->chunks(), sun)
          : lambert_;
  glUseProgram(program.id());
  glUniformMatrix4fv(program.uniform("model_view_projection"), 1, GL_FALSE, glm::value_ptr(model_view_projection_));
  if (prt) {
    transfer->bind();
    glUniform1i(program.uniform("vertices_per_chunk"), static_cast<GLint>(transfer->vertices_per_chunk()));
    glBindBufferBase(GL_UNIFORM_BUFFER, kObjectLightingBinding, object_lighting_);
    if (sun) bind_sun(program, settings, false);
  } else {
    const glm::mat3 normal_to_world = to_float(settings.object_rotation);
    const glm::vec3 light_direction(settings.environment_rotation * lambert_direction_);
    const glm::vec3 light_radiance(lambert_radiance_);
    glUniformMatrix3fv(program.uniform("normal_to_world"), 1, GL_FALSE, glm::value_ptr(normal_to_world));
    glUniform3fv(program.uniform("light_direction"), 1, glm::value_ptr(light_direction));
    glUniform3fv(program.uniform("light_radiance"), 1, glm::value_ptr(light_radiance));
  }
  glDrawElements(GL_TRIANGLES, index_count_, GL_UNSIGNED_INT, nullptr);
  if (sun) draw_sun_deferred(settings);
}

const Program& Renderer::prt_program(int channels, int coefficient_count, int used_count, int chunks, bool sun) {
  const auto key = std::make_tuple(channels, coefficient_count, used_count, chunks, sun);
  auto found = prt_programs_.find(key);
  if (found == prt_programs_.end()) {
    const std::string defines = "#define CHANNELS " + std::to_string(channels) + "\n#define COEFFICIENT_COUNT " +
                                std::to_string(coefficient_count) + "\n#define USED_COUNT " +
                                std::to_string(used_count) + "\n#define CHUNKS " + std::to_string(chunks) + "\n" +
                                (sun ? "#define SUN 1\n" : "");
    found = prt_programs_.emplace(key, Program({"prt_diffuse.vert", "surface.frag"}, defines)).first;
  }
  return found->second;
}

image::Image Renderer::read_radiance() const {
  image::Image out(width_, height_, 3);
  if (framebuffer_ == 0) return out;
  std::vector<float> rgba(static_cast<std::size_t>(width_) * height_ * 4);
  glNamedFramebufferReadBuffer(framebuffer_, GL_COLOR_ATTACHMENT0);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glReadPixels(0, 0, width_, height_, GL_RGBA, GL_FLOAT, rgba.data());
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  check_gl("reading radiance");
  // GL rows go up from the bottom; image rows go down from the top.
  for (int y = 0; y < height_; ++y) {
    const float* row = rgba.data() + static_cast<std::size_t>(height_ - 1 - y) * width_ * 4;
    for (int x = 0; x < width_; ++x)
      for (int c = 0; c < 3; ++c) out.at(x, y, c) = row[static_cast<std::size_t>(x) * 4 + c];
  }
  return out;
}

std::vector<std::uint32_t> Renderer::read_triangle_ids() const {
  std::vector<std::uint32_t> gl_rows(static_cast<std::size_t>(width_) * height_);
  if (framebuffer_ == 0) return gl_rows;
  glNamedFramebufferReadBuffer(framebuffer_, GL_COLOR_ATTACHMENT1);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glReadPixels(0, 0, width_, height_, GL_RED_INTEGER, GL_UNSIGNED_INT, gl_rows.data());
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  check_gl("reading triangle ids");
  std::vector<std::uint32_t> out(gl_rows.size());
  for (int y = 0; y < height_; ++y)
    std::memcpy(out.data() + static_cast<std::size_t>(y) * width_,
                gl_rows.data() + static_cast<std::size_t>(height_ - 1 - y) * width_, sizeof(std::uint32_t) * width_);
  return out;
}

void Renderer::present(GLuint target, double exposure_stops, image::ToneMap tone_map) {
  if (framebuffer_ == 0) return;
  glBindFramebuffer(GL_FRAMEBUFFER, target);
  glViewport(0, 0, width_, height_);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_FRAMEBUFFER_SRGB);  // the shader encodes sRGB itself, as to_display does
  glUseProgram(tonemap_.id());
  glBindVertexArray(empty_vao_);
  glBindTextureUnit(0, radiance_texture_);
  glUniform1f(tonemap_.uniform("exposure_scale"), static_cast<float>(std::exp2(exposure_stops)));
  glUniform1i(tonemap_.uniform("tone_map"), tone_map == image::ToneMap::aces ? 1 : 0);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  check_gl("presenting a frame");
}

}  // namespace prt::render
