// The frame core (frame_core.h): what every pass of the renderer shares.
#include "render/frame_core.h"

#include <algorithm>

#include <glm/gtc/type_ptr.hpp>
#include <glm/matrix.hpp>

#include "core/error.h"
#include "render/bindings.h"
#include "sh/basis.h"
#include "sh/rotation.h"

namespace prt::render {

namespace {

constexpr GLsizeiptr kLightingBytes = kMaxCoefficients * static_cast<GLsizeiptr>(sizeof(glm::vec4));
constexpr GLuint kEnvironmentLightingBinding = 1;  // background.frag: uniform EnvironmentLighting
constexpr float kDefaultAlbedo = 0.8f;
constexpr GLuint kFrameRadianceUnit = 11;  // prt_sun.frag: frame_radiance
constexpr GLuint kFrameTriangleUnit = 12;  // prt_sun.frag: frame_triangles

glm::mat3 to_float(const glm::dmat3& m) { return glm::mat3(m); }

}  // namespace

GLuint make_buffer(GLsizeiptr bytes, const void* data, GLbitfield flags) {
  GLuint buffer = 0;
  glCreateBuffers(1, &buffer);
  glNamedBufferStorage(buffer, std::max<GLsizeiptr>(bytes, 4), data, flags);
  return buffer;
}

FrameCore::FrameCore()
    : lighting(kMaxCoefficients, glm::vec3(0.0f)),
      rotated(kMaxCoefficients, glm::vec3(0.0f)),
      upload(kMaxCoefficients, glm::vec4(0.0f)),
      sun(std::make_unique<SunLight>()),
      tonemap({"fullscreen.vert", "tonemap.frag"}),
      background_({"fullscreen.vert", "background.frag"}),
      background_discs_({"fullscreen.vert", "background.frag"}, "#define DISCS 1\n"),
      lambert_({"lambert.vert", "surface.frag"}) {
  glCreateVertexArrays(1, &empty_vao);
  object_lighting = make_buffer(kLightingBytes, upload.data(), GL_DYNAMIC_STORAGE_BIT);
  environment_lighting = make_buffer(kLightingBytes, upload.data(), GL_DYNAMIC_STORAGE_BIT);
  check_gl("creating renderer");
}

FrameCore::~FrameCore() {
  sun.reset();
  for (GLuint* buffer : {&positions, &normals, &albedo, &indices, &lightmap_uv, &object_lighting, &environment_lighting})
    delete_buffer(*buffer);
  delete_texture(environment_texture);
  delete_texture(radiance_texture);
  delete_texture(triangle_texture);
  if (depth_buffer != 0) glDeleteRenderbuffers(1, &depth_buffer);
  if (framebuffer != 0) glDeleteFramebuffers(1, &framebuffer);
  if (mesh_vao != 0) glDeleteVertexArrays(1, &mesh_vao);
  if (empty_vao != 0) glDeleteVertexArrays(1, &empty_vao);
}

void FrameCore::set_mesh(const mesh::Mesh& mesh) {
  sun->clear_mesh();
  for (GLuint* buffer : {&positions, &normals, &albedo, &indices, &lightmap_uv}) delete_buffer(*buffer);
  if (mesh_vao != 0) glDeleteVertexArrays(1, &mesh_vao);
  lightmap_uv_corners = mesh.has_lightmap_uv() ? mesh.lightmap_uv.size() : 0;
  if (lightmap_uv_corners > 0)
    lightmap_uv = make_buffer(static_cast<GLsizeiptr>(lightmap_uv_corners * sizeof(glm::vec2)), mesh.lightmap_uv.data(), 0);

  const auto vec3_bytes = static_cast<GLsizeiptr>(mesh.positions.size() * sizeof(glm::vec3));
  positions = make_buffer(vec3_bytes, mesh.positions.data(), 0);
  normals = make_buffer(vec3_bytes, mesh.normals.data(), 0);
  if (mesh.albedo.size() == mesh.positions.size()) {
    albedo = make_buffer(vec3_bytes, mesh.albedo.data(), 0);
  } else {
    const std::vector<glm::vec3> grey(mesh.positions.size(), glm::vec3(kDefaultAlbedo));
    albedo = make_buffer(vec3_bytes, grey.data(), 0);
  }
  indices = make_buffer(static_cast<GLsizeiptr>(mesh.indices.size() * sizeof(std::uint32_t)), mesh.indices.data(), 0);

  glCreateVertexArrays(1, &mesh_vao);
  const GLuint sources[3] = {positions, normals, albedo};
  for (GLuint location = 0; location < 3; ++location) {
    glVertexArrayVertexBuffer(mesh_vao, location, sources[location], 0, sizeof(glm::vec3));
    glVertexArrayAttribFormat(mesh_vao, location, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(mesh_vao, location, location);
    glEnableVertexArrayAttrib(mesh_vao, location);
  }
  glVertexArrayElementBuffer(mesh_vao, indices);
  check_gl("uploading mesh");

  base_colour.set_mesh(mesh);
  index_count = static_cast<GLsizei>(mesh.indices.size());
  vertex_count = mesh.vertex_count();
  bounds = mesh::bounds(mesh);
  has_mesh = true;
}

void FrameCore::set_lighting(const sh::RgbCoefficients& coefficients, const image::Image* equirect) {
  std::fill(lighting.begin(), lighting.end(), glm::vec3(0.0f));
  const std::size_t count = std::min<std::size_t>(coefficients.values.size(), kMaxCoefficients);
  for (std::size_t i = 0; i < count; ++i) lighting[i] = glm::vec3(coefficients.values[i]);
  lighting_bands = std::max(1, std::min(coefficients.bands, sh::kMaxBands));
  for (std::size_t i = 0; i < kMaxCoefficients; ++i) upload[i] = glm::vec4(lighting[i], 0.0f);
  glNamedBufferSubData(environment_lighting, 0, kLightingBytes, upload.data());
  lambert_light(coefficients, lambert_direction, lambert_radiance);

  delete_texture(environment_texture);
  if (equirect != nullptr) {
    if (equirect->channels != 3 || equirect->width < 1 || equirect->height < 1)
      fail("renderer: the environment image must be RGB and not empty");
    glCreateTextures(GL_TEXTURE_2D, 1, &environment_texture);
    glTextureStorage2D(environment_texture, 1, GL_RGB32F, equirect->width, equirect->height);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    // Row 0 of the image (the top, v = 0, +Y) goes to texture row t = 0: the shader samples at t = v.
    glTextureSubImage2D(environment_texture, 0, 0, 0, equirect->width, equirect->height, GL_RGB, GL_FLOAT,
                        equirect->pixels.data());
    glTextureParameteri(environment_texture, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(environment_texture, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(environment_texture, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(environment_texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  }
  check_gl("uploading lighting");
}

void FrameCore::update_lighting(const glm::dmat3& environment_rotation, const glm::dmat3& object_rotation, int bands) {
  // Lighting seen in the object's frame: rotate by the environment's rotation, then undo the object's.
  const glm::mat3 rotation = to_float(glm::transpose(object_rotation) * environment_rotation);
  sh::rotate_rgb(bands, rotation, lighting.data(), rotated.data());
  const int count = bands * bands;
  for (int i = 0; i < count; ++i) upload[static_cast<std::size_t>(i)] = glm::vec4(rotated[static_cast<std::size_t>(i)], 0.0f);
  glNamedBufferSubData(object_lighting, 0, static_cast<GLsizeiptr>(count * sizeof(glm::vec4)), upload.data());
}

std::vector<glm::vec3> FrameCore::object_disc_lighting(const FrameSettings& settings, int bands) const {
  const glm::mat3 rotation(glm::transpose(settings.object_rotation) * settings.environment_rotation);
  std::vector<glm::vec3> out(static_cast<std::size_t>(bands * bands));
  sh::rotate_rgb(bands, rotation, sun->disc_lighting().data(), out.data());
  return out;
}

glm::vec3 FrameCore::eye_object(const FrameSettings& settings) const {
  return glm::vec3(view.centre + glm::transpose(settings.object_rotation) * (view.eye - view.centre));
}

void FrameCore::draw_mesh_elements() const { glDrawElements(GL_TRIANGLES, index_count, GL_UNSIGNED_INT, nullptr); }

void FrameCore::draw_mesh_elements(const Program& program, const TriangleRuns* runs) const {
  draw_indexed_runs(program, runs, static_cast<std::uint64_t>(index_count) / 3);
}

void FrameCore::begin_deferred(const Program& program, const FrameSettings& settings) const {
  glTextureBarrier();
  const GLenum radiance_only[2] = {GL_COLOR_ATTACHMENT0, GL_NONE};
  glNamedFramebufferDrawBuffers(framebuffer, 2, radiance_only);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_GREATER);
  glDepthMask(GL_FALSE);
  glUseProgram(program.id());
  glBindTextureUnit(kFrameRadianceUnit, radiance_texture);
  glBindTextureUnit(kFrameTriangleUnit, triangle_texture);
  // Mesh coordinates: p = c + R^T (world - c) (renderer.h); ray direction R^T C (ndc.x tan_x, ndc.y tan_y, -1).
  const glm::dmat3 to_object = glm::transpose(settings.object_rotation);
  const glm::dvec3 eye = view.centre + to_object * (view.eye - view.centre);
  glm::dmat3 basis = to_object * view.camera_to_world;
  basis[0] *= view.tan_half_fov_x;
  basis[1] *= view.tan_half_fov_y;
  basis[2] *= -1.0;
  const glm::mat3 ray_basis(basis);
  glUniform2f(program.uniform("frame_size"), static_cast<float>(width), static_cast<float>(height));
  glUniform3f(program.uniform("eye_object"), static_cast<float>(eye.x), static_cast<float>(eye.y), static_cast<float>(eye.z));
  glUniformMatrix3fv(program.uniform("ray_basis"), 1, GL_FALSE, glm::value_ptr(ray_basis));
}

void FrameCore::end_deferred() const {
  glBindVertexArray(empty_vao);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  const GLenum both[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  glNamedFramebufferDrawBuffers(framebuffer, 2, both);
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LESS);
}

void FrameCore::resize(int new_width, int new_height) {
  if (new_width == width && new_height == height && framebuffer != 0) return;
  delete_texture(radiance_texture);
  delete_texture(triangle_texture);
  if (depth_buffer != 0) glDeleteRenderbuffers(1, &depth_buffer);
  if (framebuffer != 0) glDeleteFramebuffers(1, &framebuffer);

  glCreateTextures(GL_TEXTURE_2D, 1, &radiance_texture);
  glTextureStorage2D(radiance_texture, 1, GL_RGBA32F, new_width, new_height);
  glCreateTextures(GL_TEXTURE_2D, 1, &triangle_texture);
  glTextureStorage2D(triangle_texture, 1, GL_R32UI, new_width, new_height);
  for (GLuint texture : {radiance_texture, triangle_texture}) {
    glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  }
  glCreateRenderbuffers(1, &depth_buffer);
  glNamedRenderbufferStorage(depth_buffer, GL_DEPTH_COMPONENT32F, new_width, new_height);
  glCreateFramebuffers(1, &framebuffer);
  glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, radiance_texture, 0);
  glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT1, triangle_texture, 0);
  glNamedFramebufferRenderbuffer(framebuffer, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_buffer);
  const GLenum draw_buffers[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  glNamedFramebufferDrawBuffers(framebuffer, 2, draw_buffers);
  if (glCheckNamedFramebufferStatus(framebuffer, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    fail("renderer: cannot create a " + std::to_string(new_width) + "x" + std::to_string(new_height) + " float framebuffer");
  check_gl("creating framebuffer");
  width = new_width;
  height = new_height;
}

void FrameCore::set_view(const Camera& camera, const glm::dmat3& object_rotation, int frame_width, int frame_height) {
  view = orbit_view(camera, bounds, frame_width, frame_height, object_rotation);
  model_view_projection = glm::mat4(view.projection * view.view * view.model);
}

void FrameCore::begin_frame(bool depth) {
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  glViewport(0, 0, width, height);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glDisable(GL_SCISSOR_TEST);
  if (depth) {
    glDisable(GL_FRAMEBUFFER_SRGB);
    glDepthMask(GL_TRUE);
  }
  const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  const GLuint none[4] = {kNoTriangle, 0, 0, 0};
  glClearNamedFramebufferfv(framebuffer, GL_COLOR, 0, zero);
  glClearNamedFramebufferuiv(framebuffer, GL_COLOR, 1, none);
  const float far_depth = 1.0f;
  if (depth) glClearNamedFramebufferfv(framebuffer, GL_DEPTH, 0, &far_depth);
}

void FrameCore::draw_background(const FrameSettings& settings, int bands) {
  if (settings.background == Background::black) return;  // the clear colour is black
  glDisable(GL_DEPTH_TEST);
  draw_background_pass(background_, settings, bands);
  if (!settings.sun || sun->discs().empty()) return;
  // The sky again with the discs, over each disc's rectangle only (the disc program costs per pixel).
  glEnable(GL_SCISSOR_TEST);
  for (const light::Disc& disc : sun->discs()) {
    const auto rect = camera::cap_pixel_rect(view, width, height, settings.environment_rotation * disc.direction,
                                             disc.angular_radius);
    if (!rect) continue;
    glScissor(rect->x0, rect->y0, rect->x1 - rect->x0, rect->y1 - rect->y0);
    draw_background_pass(background_discs_, settings, bands);
  }
  glDisable(GL_SCISSOR_TEST);
}

void FrameCore::draw_background_pass(const Program& program, const FrameSettings& settings, int bands) {
  glUseProgram(program.id());
  glBindVertexArray(empty_vao);
  glBindBufferBase(GL_UNIFORM_BUFFER, kEnvironmentLightingBinding, environment_lighting);
  if (environment_texture != 0) glBindTextureUnit(0, environment_texture);
  const glm::mat3 camera_to_world = to_float(view.camera_to_world);
  const glm::mat3 world_to_environment = to_float(glm::transpose(settings.environment_rotation));
  glUniformMatrix3fv(program.uniform("camera_to_world"), 1, GL_FALSE, glm::value_ptr(camera_to_world));
  glUniformMatrix3fv(program.uniform("world_to_environment"), 1, GL_FALSE, glm::value_ptr(world_to_environment));
  glUniform2f(program.uniform("tan_half_fov"), static_cast<float>(view.tan_half_fov_x), static_cast<float>(view.tan_half_fov_y));
  glUniform1i(program.uniform("mode"), settings.background == Background::environment ? 1 : 2);
  glUniform1i(program.uniform("sh_bands"), bands);
  if (&program == &background_discs_) sun->bind_background(program);
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

void FrameCore::draw_lambert(const FrameSettings& settings) {
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glBindVertexArray(mesh_vao);
  glUseProgram(lambert_.id());
  glUniformMatrix4fv(lambert_.uniform("model_view_projection"), 1, GL_FALSE, glm::value_ptr(model_view_projection));
  const glm::mat3 normal_to_world = to_float(settings.object_rotation);
  const glm::vec3 light_direction(settings.environment_rotation * lambert_direction);
  const glm::vec3 light_radiance(lambert_radiance);
  glUniformMatrix3fv(lambert_.uniform("normal_to_world"), 1, GL_FALSE, glm::value_ptr(normal_to_world));
  glUniform3fv(lambert_.uniform("light_direction"), 1, glm::value_ptr(light_direction));
  glUniform3fv(lambert_.uniform("light_radiance"), 1, glm::value_ptr(light_radiance));
  draw_mesh_elements();
}

const Program& FrameCore::program(const std::vector<std::string>& stages, const std::string& defines) {
  std::string name;
  for (const std::string& stage : stages) name += stage + "+";
  const auto key = std::make_pair(name, defines);
  auto found = programs_.find(key);
  if (found == programs_.end()) found = programs_.emplace(key, Program(stages, defines)).first;
  return found->second;
}

}  // namespace prt::render
