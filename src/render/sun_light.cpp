// The sun (sun_light.h; renderer.h, PASSES: sun): discs, their shadow maps, and the uniforms the SUN
// variants of the passes read (shaders/sun_light.glsl).
#include "render/sun_light.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/geometric.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/matrix.hpp>

#include "core/error.h"
#include "render/bindings.h"
#include "render/frame_core.h"
#include "sh/basis.h"

namespace prt::render {

namespace {

constexpr GLuint kSunAlbedoBinding = 6;       // prt_diffuse.vert, prt_lightmap.vert (SUN); sun_visibility.comp: Visibility
constexpr GLuint kShadowUnit = 8;             // sun_light.glsl: shadow_maps
constexpr int kMaxTerms = kMaxBrdfTerms;
constexpr GLuint kBrdfTermsBinding = 8;      // sun_light.glsl (BRDF_TABLE): buffer BrdfTerms
constexpr GLuint kTileUnit = 9;               // sun_light.glsl: shadow_tiles
constexpr GLuint kTriangleCornersUnit = 13;   // prt_sun.frag: triangle_corners
constexpr GLuint kSurfaceUnit = 14;           // prt_sun.frag: surface
constexpr int kShadowTile = 32;               // texels per tile side; > 2 x sun_light.glsl's max_filter
constexpr int kFilterCount = 12;              // sun_light.glsl: filter_count, the PCF filter's samples
constexpr int kTiles = kShadowMapSize / kShadowTile;

void release_texture(GLuint& texture) {
  if (texture != 0) glDeleteTextures(1, &texture);
  texture = 0;
}

// A buffer texture over `bytes` of `data` (immutable) with texel format `format`.
void buffer_texture(const void* data, std::size_t bytes, GLenum format, GLuint& buffer, GLuint& texture) {
  buffer = make_buffer(static_cast<GLsizeiptr>(std::max<std::size_t>(bytes, 16)), data, 0);
  glCreateTextures(GL_TEXTURE_BUFFER, 1, &texture);
  glTextureBuffer(texture, format, buffer);
}

template <typename T>
std::vector<T> read_buffer(GLuint buffer, std::size_t count) {
  std::vector<T> out(count);
  glGetNamedBufferSubData(buffer, 0, static_cast<GLsizeiptr>(count * sizeof(T)), out.data());
  return out;
}

// A unit vector perpendicular to d (the Duff et al. 2017 basis's first axis).
glm::dvec3 perpendicular(const glm::dvec3& n) {
  const double sign = std::copysign(1.0, n.z);
  const double a = -1.0 / (sign + n.z);
  return glm::dvec3(1.0 + sign * n.x * n.x * a, sign * n.x * n.y * a, -sign * n.x);
}

// The lookups' variant for this context (sun_light.glsl): without the tile early-outs on a software
// rasteriser (Mesa's llvmpipe or softpipe), where branches skip no work.
std::string lookup_defines() {
  const auto* name = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const std::string renderer = name != nullptr ? name : "";
  const bool software = renderer.find("llvmpipe") != std::string::npos || renderer.find("softpipe") != std::string::npos;
  return software ? "#define SUN_TILE_EARLY_OUTS 0\n" : "";
}

}  // namespace

SunSurface::~SunSurface() {
  delete_buffer(albedo);
  delete_buffer(surface_buffer);
  delete_buffer(term_table);
  release_texture(surface_texture);
}

void SunSurface::set_albedo(const std::vector<glm::vec3>& values) {
  delete_buffer(surface_buffer);  // rebuilt with this albedo on the next deferred pass
  release_texture(surface_texture);
  delete_buffer(albedo);
  glCreateBuffers(1, &albedo);
  glNamedBufferStorage(albedo, static_cast<GLsizeiptr>(values.size() * sizeof(glm::vec3)), values.data(), 0);
}

SunLight::SunLight()
    : disc_lighting_(kMaxCoefficients, glm::vec3(0.0f)),
      shadow_program_({"shadow.vert"}),
      visibility_program_({"sun_visibility.comp"}, lookup_defines()),
      minmax_program_({"shadow_minmax.comp"}),
      deferred_program_({"sun_fullscreen.vert", "prt_sun.frag"}, lookup_defines()) {
  glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &shadow_texture_);
  glTextureStorage3D(shadow_texture_, 1, GL_DEPTH_COMPONENT32F, kShadowMapSize, kShadowMapSize, kMaxDiscs);
  glTextureParameteri(shadow_texture_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(shadow_texture_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTextureParameteri(shadow_texture_, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_BORDER);
  glTextureParameteri(shadow_texture_, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_BORDER);
  const float far[4] = {1.0f, 1.0f, 1.0f, 1.0f};  // outside the map: nothing between it and the light
  glTextureParameterfv(shadow_texture_, GL_TEXTURE_BORDER_COLOR, far);
  glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &tile_texture_);
  glTextureStorage3D(tile_texture_, 1, GL_RG32F, kTiles, kTiles, kMaxDiscs);
  glTextureParameteri(tile_texture_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(tile_texture_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glCreateFramebuffers(1, &shadow_framebuffer_);
  glNamedFramebufferDrawBuffer(shadow_framebuffer_, GL_NONE);
  glNamedFramebufferReadBuffer(shadow_framebuffer_, GL_NONE);
  check_gl("creating the sun pass");
}

SunLight::~SunLight() {
  clear_mesh();
  release_texture(shadow_texture_);
  release_texture(tile_texture_);
  if (shadow_framebuffer_ != 0) glDeleteFramebuffers(1, &shadow_framebuffer_);
}

void SunLight::clear_mesh() {
  delete_buffer(triangle_buffer_);
  release_texture(triangle_texture_);
  maps_valid_ = false;
}

void SunLight::set_discs(const std::vector<light::Disc>& discs) {
  discs_.assign(discs.begin(), discs.begin() + std::min<std::ptrdiff_t>(discs.size(), kMaxDiscs));
  const sh::RgbCoefficients sh = light::discs_coefficients(sh::kMaxBands, discs_);
  for (std::size_t i = 0; i < disc_lighting_.size(); ++i) disc_lighting_[i] = glm::vec3(sh.values[i]);
  ++version_;
}

void SunLight::bind_background(const Program& program) const {
  const int n = static_cast<int>(discs_.size());
  glm::vec3 direction[kMaxDiscs], radiance[kMaxDiscs];
  float chord[kMaxDiscs];
  for (int k = 0; k < n; ++k) {
    const light::Disc& disc = discs_[static_cast<std::size_t>(k)];
    direction[k] = glm::vec3(disc.direction);
    radiance[k] = glm::vec3(disc.radiance());
    chord[k] = static_cast<float>(2.0 * std::sin(0.5 * disc.angular_radius));
  }
  glUniform1i(program.uniform("disc_count"), n);
  glUniform3fv(program.uniform("disc_direction"), n, glm::value_ptr(direction[0]));
  glUniform3fv(program.uniform("disc_radiance"), n, glm::value_ptr(radiance[0]));
  glUniform1fv(program.uniform("disc_chord"), n, chord);
}

void SunLight::update_maps(const FrameCore& core, const glm::dmat3& rotation) {
  if (maps_valid_ && maps_version_ == version_ && maps_rotation_ == rotation) return;
  for (std::size_t k = 0; k < discs_.size(); ++k) direction_[k] = glm::vec3(glm::normalize(rotation * discs_[k].direction));
  draw_maps(core);
  maps_valid_ = true;
  maps_version_ = version_;
  maps_rotation_ = rotation;
  ++updates_;
}

// One orthographic depth map per disc, looking along -d (object frame), fitted to the bounds' corners:
// a square of half-width h about their centre across d, the depth range their extent along d.
void SunLight::draw_maps(const FrameCore& core) {
  const glm::dvec3 lo(core.bounds.lo), hi(core.bounds.hi);
  const double margin = 1e-3 * std::max(1e-12, glm::length(hi - lo));
  for (std::size_t k = 0; k < discs_.size(); ++k) {
    const glm::dvec3 d = glm::normalize(glm::dvec3(direction_[k]));
    const glm::dvec3 u = glm::normalize(perpendicular(d)), v = glm::cross(d, u);
    glm::dvec3 min_c(1e300), max_c(-1e300);
    for (int corner = 0; corner < 8; ++corner) {
      const glm::dvec3 p((corner & 1) ? hi.x : lo.x, (corner & 2) ? hi.y : lo.y, (corner & 4) ? hi.z : lo.z);
      const glm::dvec3 c(glm::dot(p, u), glm::dot(p, v), glm::dot(p, d));
      min_c = glm::min(min_c, c);
      max_c = glm::max(max_c, c);
    }
    const double half = 0.5 * std::max(max_c.x - min_c.x, max_c.y - min_c.y) + margin;
    const double cu = 0.5 * (min_c.x + max_c.x), cv = 0.5 * (min_c.y + max_c.y);
    const double top = max_c.z + margin, depth_range = max_c.z - min_c.z + 2.0 * margin;
    // clip x = (p.u - cu) / half, y = (p.v - cv) / half, z = 2 (top - p.d) / range - 1 (depth 0 at the top).
    glm::dmat4 m(0.0);
    for (int i = 0; i < 3; ++i) {
      m[i][0] = u[i] / half;
      m[i][1] = v[i] / half;
      m[i][2] = -2.0 * d[i] / depth_range;
    }
    m[3] = glm::dvec4(-cu / half, -cv / half, 2.0 * top / depth_range - 1.0, 1.0);
    glm::dmat4 to_unit(0.5);  // clip -> [0,1]^3
    to_unit[3] = glm::dvec4(0.5, 0.5, 0.5, 1.0);
    light_projection_[k] = glm::mat4(m);
    shadow_matrix_[k] = glm::mat4(to_unit * m);
    texel_[k] = static_cast<float>(2.0 * half / kShadowMapSize);
    depth_scale_[k] = static_cast<float>(depth_range);
  }
  glBindFramebuffer(GL_FRAMEBUFFER, shadow_framebuffer_);
  glViewport(0, 0, kShadowMapSize, kShadowMapSize);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glDisable(GL_CULL_FACE);  // both sides occlude, as shadow rays meet triangles from either side
  glUseProgram(shadow_program_.id());
  glBindVertexArray(core.mesh_vao);
  const float far_depth = 1.0f;
  for (std::size_t k = 0; k < discs_.size(); ++k) {
    glNamedFramebufferTextureLayer(shadow_framebuffer_, GL_DEPTH_ATTACHMENT, shadow_texture_, 0, static_cast<GLint>(k));
    glClearNamedFramebufferfv(shadow_framebuffer_, GL_DEPTH, 0, &far_depth);
    glUniformMatrix4fv(shadow_program_.uniform("light_projection"), 1, GL_FALSE, glm::value_ptr(light_projection_[k]));
    core.draw_mesh_elements();
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  // Each tile's least and greatest depth, for the exact early-outs of sun_light.glsl.
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
  glUseProgram(minmax_program_.id());
  glBindTextureUnit(kShadowUnit, shadow_texture_);
  glBindImageTexture(0, tile_texture_, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RG32F);
  glUniform1i(minmax_program_.uniform("shadow_tile"), kShadowTile);
  glDispatchCompute(kTiles / 8, kTiles / 8, static_cast<GLuint>(discs_.size()));
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
  check_gl("drawing shadow maps");
}

// Depth-only draw of the mesh with the frame's model-view-projection, then depth test LEQUAL (rewriting
// the same depth): the SUN fragment stage that follows (the shadow-map lookups) runs once per covered
// pixel, on the nearest surface only, instead of once per rasterised fragment (overdraw). shadow.vert and the
// SUN vertex stages declare gl_Position invariant, so both draws give each pixel the same depth.
void SunLight::draw_prepass(const FrameCore& core) const {
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  glUseProgram(shadow_program_.id());
  glUniformMatrix4fv(shadow_program_.uniform("light_projection"), 1, GL_FALSE, glm::value_ptr(core.model_view_projection));
  glBindVertexArray(core.mesh_vao);
  core.draw_mesh_elements();
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDepthFunc(GL_LEQUAL);
}

// The deferred pass's mesh data as buffer textures (cheaper per-pixel reads than storage buffers on
// llvmpipe): per triangle its corner indices (RGBA32UI), per vertex of the surface three texels
// (RGBA32F) position, normal, albedo; made on first use from the GL buffers.
void SunLight::bind_surface(const FrameCore& core, SunSurface& t) {
  if (triangle_texture_ == 0) {
    const std::vector<std::uint32_t> indices = read_buffer<std::uint32_t>(core.indices, static_cast<std::size_t>(core.index_count));
    std::vector<glm::uvec4> packed(indices.size() / 3);
    for (std::size_t i = 0; i < packed.size(); ++i) packed[i] = glm::uvec4(indices[3 * i], indices[3 * i + 1], indices[3 * i + 2], 0u);
    buffer_texture(packed.data(), packed.size() * sizeof(glm::uvec4), GL_RGBA32UI, triangle_buffer_, triangle_texture_);
  }
  if (t.surface_texture == 0) {
    const std::size_t n = core.vertex_count;
    const std::vector<glm::vec3> positions = read_buffer<glm::vec3>(core.positions, n);
    const std::vector<glm::vec3> normals = read_buffer<glm::vec3>(core.normals, n);
    const std::vector<glm::vec3> albedo = read_buffer<glm::vec3>(t.albedo != 0 ? t.albedo : core.albedo, n);
    std::vector<glm::vec4> packed(3 * n);
    for (std::size_t v = 0; v < n; ++v) {
      packed[3 * v] = glm::vec4(positions[v], 0.0f);
      packed[3 * v + 1] = glm::vec4(normals[v], 0.0f);
      packed[3 * v + 2] = glm::vec4(albedo[v], 0.0f);
    }
    buffer_texture(packed.data(), packed.size() * sizeof(glm::vec4), GL_RGBA32F, t.surface_buffer, t.surface_texture);
  }
  glBindTextureUnit(kTriangleCornersUnit, triangle_texture_);
  glBindTextureUnit(kSurfaceUnit, t.surface_texture);
}

// The discs' direct light for diffuse transfer, deferred: after the mesh draw (sky and bounce light,
// unclamped, and the triangle index per pixel), one full-viewport draw at the far plane with the depth
// test GREATER reaches each covered pixel exactly once (prt_sun.frag), reads that pixel's radiance and
// triangle, and writes the clamped sum. Attachment 1 is not written in it; each pixel of attachment 0
// is read and written by its own fragment only (the texture barrier makes the mesh draw's writes
// visible to it).
void SunLight::draw_deferred(FrameCore& core, const FrameSettings& settings, SunSurface& surface,
                             const BaseColour* base_colour) {
  const Program& program = base_colour != nullptr
                               ? core.program({"sun_fullscreen.vert", "prt_sun.frag"}, lookup_defines() + base_colour->defines())
                               : deferred_program_;
  core.begin_deferred(program, settings);
  bind(core, program, surface, false);
  bind_surface(core, surface);
  if (base_colour != nullptr) {
    base_colour->bind(program);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kIndicesBinding, core.indices);
  }
  core.end_deferred();
}

void SunLight::bind(const FrameCore& core, const Program& program, const SunSurface& t, bool glossy) const {
  const int n = static_cast<int>(discs_.size());
  glm::vec3 irradiance[kMaxDiscs];
  float tan_radius[kMaxDiscs];
  for (int k = 0; k < n; ++k) {
    irradiance[k] = glm::vec3(discs_[static_cast<std::size_t>(k)].irradiance);
    tan_radius[k] = static_cast<float>(std::tan(discs_[static_cast<std::size_t>(k)].angular_radius));
  }
  glUniform1i(program.uniform("disc_count"), n);
  glUniform3fv(program.uniform("disc_direction"), n, glm::value_ptr(direction_[0]));
  glUniform3fv(program.uniform("disc_irradiance"), n, glm::value_ptr(irradiance[0]));
  glUniform1fv(program.uniform("disc_tan_radius"), n, tan_radius);
  glUniformMatrix4fv(program.uniform("shadow_matrix"), n, GL_FALSE, glm::value_ptr(shadow_matrix_[0]));
  glUniform1fv(program.uniform("shadow_depth_scale"), n, depth_scale_.data());
  glUniform1fv(program.uniform("shadow_texel"), n, texel_.data());
  glUniform1i(program.uniform("disc_shadows"), t.shadows ? 1 : 0);
  glBindTextureUnit(kShadowUnit, shadow_texture_);
  glBindTextureUnit(kTileUnit, tile_texture_);
  glUniform1i(program.uniform("shadow_tile"), kShadowTile);
  glUniform1i(program.uniform("filter_count"), kFilterCount);
  if (!glossy) {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kSunAlbedoBinding, t.albedo != 0 ? t.albedo : core.albedo);
    return;
  }
  if (t.term_table != 0) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBrdfTermsBinding, t.term_table);
  const int terms = static_cast<int>(t.terms.size());
  GLint shapes[kMaxTerms];
  float parameters[kMaxTerms];
  glm::vec3 weights[kMaxTerms];
  for (int i = 0; i < terms; ++i) {
    shapes[i] = static_cast<GLint>(t.terms[static_cast<std::size_t>(i)].shape);
    parameters[i] = static_cast<float>(t.terms[static_cast<std::size_t>(i)].parameter);
    weights[i] = glm::vec3(t.terms[static_cast<std::size_t>(i)].weight);
  }
  glUniform1i(program.uniform("brdf_term_count"), terms);
  if (terms > 0) {
    glUniform1iv(program.uniform("brdf_shape"), terms, shapes);
    glUniform1fv(program.uniform("brdf_parameter"), terms, parameters);
    glUniform3fv(program.uniform("brdf_weight"), terms, glm::value_ptr(weights[0]));
  }
}

std::vector<float> SunLight::visibility(const FrameCore& core, int disc) const {
  const Program& program = visibility_program_;
  glUseProgram(program.id());
  const SunSurface any;
  bind(core, program, any, false);
  glUniform1i(program.uniform("disc_shadows"), 1);
  glUniform1i(program.uniform("vertex_count"), static_cast<GLint>(core.vertex_count));
  glUniform1i(program.uniform("disc"), disc);
  GLuint output = make_buffer(static_cast<GLsizeiptr>(std::max<std::size_t>(core.vertex_count * sizeof(float), 16)), nullptr,
                              GL_DYNAMIC_STORAGE_BIT);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPositionsBinding, core.positions);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kNormalsBinding, core.normals);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kSunAlbedoBinding, output);
  glDispatchCompute(static_cast<GLuint>((core.vertex_count + kWorkgroupSize - 1) / kWorkgroupSize), 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::vector<float> out(core.vertex_count);
  glGetNamedBufferSubData(output, 0, static_cast<GLsizeiptr>(out.size() * sizeof(float)), out.data());
  delete_buffer(output);
  check_gl("measuring shadow-map visibility");
  return out;
}

}  // namespace prt::render
