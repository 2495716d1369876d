// The renderer's sun pass (renderer.h, PASSES: sun): discs, their shadow maps, their bounce light and
// the uniforms the SUN variants of the PRT passes read (shaders/sun_light.glsl).
#include "render/renderer_sun.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <glm/geometric.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/matrix.hpp>

#include "core/error.h"
#include "sh/basis.h"
#include "sh/rotation.h"
#include "shade/shade.h"

namespace prt::render {

namespace {

constexpr int kMaxCoefficients = sh::kMaxBands * sh::kMaxBands;
constexpr GLuint kLightingBinding = 0;        // prt_glossy.comp: uniform Lighting
constexpr GLuint kBrdfBinding = 1;            // prt_glossy.comp: buffer BrdfMatrix
constexpr GLuint kOutgoingBinding = 2;        // prt_glossy.comp: buffer Outgoing
constexpr GLuint kPositionsBinding = 4;       // sun_visibility.comp
constexpr GLuint kNormalsBinding = 5;         // sun_visibility.comp
constexpr GLuint kSunAlbedoBinding = 6;       // prt_diffuse.vert (SUN); sun_visibility.comp: Visibility
constexpr GLuint kSunBounceBinding = 7;       // prt_diffuse.vert (SUN)
constexpr GLuint kBounceOutgoingBinding = 6;  // prt_glossy.comp (SUN)
constexpr GLuint kShadowUnit = 8;             // sun_light.glsl: shadow_maps
constexpr GLuint kWorkgroupSize = 64;
constexpr int kMaxTerms = 8;                  // sun_light.glsl: max_terms
constexpr GLuint kTileUnit = 9;               // sun_light.glsl: shadow_tiles
constexpr GLuint kFrameRadianceUnit = 11;     // prt_sun.frag: frame_radiance
constexpr GLuint kFrameTriangleUnit = 12;     // prt_sun.frag: frame_triangles
constexpr GLuint kTriangleCornersUnit = 13;   // prt_sun.frag: triangle_corners
constexpr GLuint kSurfaceUnit = 14;           // prt_sun.frag: surface
constexpr int kShadowTile = 32;               // texels per tile side; > 2 x sun_light.glsl's max_filter
constexpr int kFilterCount = 12;              // sun_light.glsl: filter_count, the PCF filter's samples
constexpr int kTiles = kShadowMapSize / kShadowTile;

GLuint dynamic_buffer(std::size_t bytes) {
  GLuint buffer = 0;
  glCreateBuffers(1, &buffer);
  glNamedBufferStorage(buffer, static_cast<GLsizeiptr>(std::max<std::size_t>(bytes, 16)), nullptr, GL_DYNAMIC_STORAGE_BIT);
  return buffer;
}

void release(GLuint& buffer) {
  if (buffer != 0) glDeleteBuffers(1, &buffer);
  buffer = 0;
}

void release_texture(GLuint& texture) {
  if (texture != 0) glDeleteTextures(1, &texture);
  texture = 0;
}

// A buffer texture over `bytes` of `data` (immutable) with texel format `format`.
void buffer_texture(const void* data, std::size_t bytes, GLenum format, GLuint& buffer, GLuint& texture) {
  glCreateBuffers(1, &buffer);
  glNamedBufferStorage(buffer, static_cast<GLsizeiptr>(std::max<std::size_t>(bytes, 16)), data, 0);
  glCreateTextures(GL_TEXTURE_BUFFER, 1, &texture);
  glTextureBuffer(texture, format, buffer);
}

template <typename T>
std::vector<T> read_buffer(GLuint buffer, std::size_t count) {
  std::vector<T> out(count);
  glGetNamedBufferSubData(buffer, 0, static_cast<GLsizeiptr>(count * sizeof(T)), out.data());
  return out;
}

bool interreflects(transfer::Kind kind) {
  return kind == transfer::Kind::interreflected || kind == transfer::Kind::glossy_interreflected;
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

Renderer::SunPass::SunPass()
    : disc_lighting(kMaxCoefficients, glm::vec3(0.0f)),
      shadow_program({"shadow.vert"}),
      visibility_program({"sun_visibility.comp"}, lookup_defines()),
      minmax_program({"shadow_minmax.comp"}),
      deferred_program({"sun_fullscreen.vert", "prt_sun.frag"}, lookup_defines()) {
  glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &shadow_texture);
  glTextureStorage3D(shadow_texture, 1, GL_DEPTH_COMPONENT32F, kShadowMapSize, kShadowMapSize, kMaxDiscs);
  glTextureParameteri(shadow_texture, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(shadow_texture, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTextureParameteri(shadow_texture, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_BORDER);
  glTextureParameteri(shadow_texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_BORDER);
  const float far[4] = {1.0f, 1.0f, 1.0f, 1.0f};  // outside the map: nothing between it and the light
  glTextureParameterfv(shadow_texture, GL_TEXTURE_BORDER_COLOR, far);
  glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &tile_texture);
  glTextureStorage3D(tile_texture, 1, GL_RG32F, kTiles, kTiles, kMaxDiscs);
  glTextureParameteri(tile_texture, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(tile_texture, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glCreateFramebuffers(1, &shadow_framebuffer);
  glNamedFramebufferDrawBuffer(shadow_framebuffer, GL_NONE);
  glNamedFramebufferReadBuffer(shadow_framebuffer, GL_NONE);
  disc_lighting_buffer = dynamic_buffer(kMaxCoefficients * sizeof(glm::vec4));
  check_gl("creating the sun pass");
}

Renderer::SunPass::~SunPass() {
  clear_mesh();
  if (shadow_texture != 0) glDeleteTextures(1, &shadow_texture);
  if (tile_texture != 0) glDeleteTextures(1, &tile_texture);
  if (shadow_framebuffer != 0) glDeleteFramebuffers(1, &shadow_framebuffer);
  release(disc_lighting_buffer);
}

void Renderer::SunPass::clear_mesh() {
  for (PerTransfer& t : transfers) {
    release(t.albedo);
    release(t.surface_buffer);
    release_texture(t.surface_texture);
  }
  release(triangle_buffer);
  release_texture(triangle_texture);
  transfers.clear();
  release(bounce_vertex);
  release(bounce_outgoing);
  bounce_outgoing_bytes = 0;
  maps_valid = bounce_valid = false;
}

void Renderer::SunPass::add_transfer(const transfer::TransferData& transfer, const std::string& origin,
                                     std::size_t max_range_bytes) {
  PerTransfer t;
  t.origin = origin;
  t.glossy = transfer::is_glossy(transfer.header.kind);
  t.shadows = transfer.header.kind != transfer::Kind::unshadowed;
  t.interreflected = interreflects(transfer.header.kind);
  if (t.interreflected && !transfer.bounce_only.empty()) {
    transfer::TransferData part;
    part.header = transfer.header;
    part.header.bounce_only_section = false;
    part.values = transfer.bounce_only;
    if (t.glossy)
      t.bounce_gpu = std::make_unique<TransferBuffer>(part, origin + " (bounce-only part)", max_range_bytes);
    else
      t.bounce_cpu = std::move(part);
  }
  transfers.push_back(std::move(t));
}

// ---------------------------------------------------------------------------------------------------
void Renderer::set_discs(const std::vector<light::Disc>& discs) {
  SunPass& s = *sun_;
  s.discs.assign(discs.begin(), discs.begin() + std::min<std::ptrdiff_t>(discs.size(), kMaxDiscs));
  const sh::RgbCoefficients sh = light::discs_coefficients(sh::kMaxBands, s.discs);
  for (std::size_t i = 0; i < s.disc_lighting.size(); ++i) s.disc_lighting[i] = glm::vec3(sh.values[i]);
  ++s.disc_version;
  ++s.version;
}

int Renderer::disc_count() const { return static_cast<int>(sun_->discs.size()); }
int Renderer::shadow_map_updates() const { return sun_->updates; }

void Renderer::bind_background_discs() {
  const std::vector<light::Disc>& discs = sun_->discs;
  const int n = static_cast<int>(discs.size());
  glm::vec3 direction[kMaxDiscs], radiance[kMaxDiscs];
  float chord[kMaxDiscs];
  for (int k = 0; k < n; ++k) {
    const light::Disc& disc = discs[static_cast<std::size_t>(k)];
    direction[k] = glm::vec3(disc.direction);
    radiance[k] = glm::vec3(disc.radiance());
    chord[k] = static_cast<float>(2.0 * std::sin(0.5 * disc.angular_radius));
  }
  glUniform1i(background_discs_.uniform("disc_count"), n);
  glUniform3fv(background_discs_.uniform("disc_direction"), n, glm::value_ptr(direction[0]));
  glUniform3fv(background_discs_.uniform("disc_radiance"), n, glm::value_ptr(radiance[0]));
  glUniform1fv(background_discs_.uniform("disc_chord"), n, chord);
}

void Renderer::set_surface_albedo(int transfer, const std::vector<glm::vec3>& albedo) {
  transfer_header(transfer);  // checks the index
  if (albedo.size() != vertex_count_)
    fail("renderer: surface albedo has " + std::to_string(albedo.size()) + " entries for " + std::to_string(vertex_count_) +
         " vertices");
  SunPass::PerTransfer& t = sun_->transfers[static_cast<std::size_t>(transfer)];
  release(t.surface_buffer);  // rebuilt with this albedo on the next deferred pass
  release_texture(t.surface_texture);
  GLuint& buffer = t.albedo;
  release(buffer);
  glCreateBuffers(1, &buffer);
  glNamedBufferStorage(buffer, static_cast<GLsizeiptr>(albedo.size() * sizeof(glm::vec3)), albedo.data(), 0);
}

void Renderer::set_brdf(int transfer, const brdf::BrdfMatrix& matrix, const brdf::Brdf& surface) {
  const std::vector<brdf::Term> terms = brdf::terms(surface);
  if (terms.size() > static_cast<std::size_t>(kMaxTerms))
    fail("renderer: the BRDF has " + std::to_string(terms.size()) + " terms; the disc term evaluates at most " +
         std::to_string(kMaxTerms));
  set_brdf(transfer, matrix);
  SunPass::PerTransfer& t = sun_->transfers[static_cast<std::size_t>(transfer)];
  t.terms = terms;
  t.has_terms = true;
  ++sun_->version;  // the glossy bounce light goes through B
}

bool Renderer::sun_active(const FrameSettings& settings) const {
  return settings.sun && settings.shading == Shading::prt && !sun_->discs.empty();
}

void Renderer::update_sun(const FrameSettings& settings, int bands) {
  SunPass& s = *sun_;
  const SunPass::PerTransfer& t = s.transfers[static_cast<std::size_t>(settings.transfer)];
  if (t.glossy && !t.has_terms)
    fail("renderer: glossy transfer " + std::to_string(settings.transfer) +
         " has no BRDF for the discs' direct light (set_brdf with the Brdf)");
  const glm::dmat3 rotation = glm::transpose(settings.object_rotation) * settings.environment_rotation;
  if (!s.maps_valid || s.maps_version != s.disc_version || s.maps_rotation != rotation) {
    for (std::size_t k = 0; k < s.discs.size(); ++k) s.direction[k] = glm::vec3(glm::normalize(rotation * s.discs[k].direction));
    draw_shadow_maps();
    s.maps_valid = true;
    s.maps_version = s.disc_version;
    s.maps_rotation = rotation;
    ++s.updates;
  }
  if (!s.bounce_valid || s.bounce_version != s.version || s.bounce_rotation != rotation ||
      s.bounce_transfer != settings.transfer || s.bounce_bands != bands) {
    update_bounce(settings, bands);
    s.bounce_valid = true;
    s.bounce_version = s.version;
    s.bounce_rotation = rotation;
    s.bounce_transfer = settings.transfer;
    s.bounce_bands = bands;
  }
}

// One orthographic depth map per disc, looking along -d (object frame), fitted to the bounds' corners:
// a square of half-width h about their centre across d, the depth range their extent along d.
void Renderer::draw_shadow_maps() {
  SunPass& s = *sun_;
  const glm::dvec3 lo(bounds_.lo), hi(bounds_.hi);
  const double margin = 1e-3 * std::max(1e-12, glm::length(hi - lo));
  for (std::size_t k = 0; k < s.discs.size(); ++k) {
    const glm::dvec3 d = glm::normalize(glm::dvec3(s.direction[k]));
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
    s.light_projection[k] = glm::mat4(m);
    s.shadow_matrix[k] = glm::mat4(to_unit * m);
    s.texel[k] = static_cast<float>(2.0 * half / kShadowMapSize);
    s.depth_scale[k] = static_cast<float>(depth_range);
  }
  glBindFramebuffer(GL_FRAMEBUFFER, s.shadow_framebuffer);
  glViewport(0, 0, kShadowMapSize, kShadowMapSize);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glDisable(GL_CULL_FACE);  // both sides occlude, as shadow rays meet triangles from either side
  glUseProgram(s.shadow_program.id());
  glBindVertexArray(mesh_vao_);
  const float far_depth = 1.0f;
  for (std::size_t k = 0; k < s.discs.size(); ++k) {
    glNamedFramebufferTextureLayer(s.shadow_framebuffer, GL_DEPTH_ATTACHMENT, s.shadow_texture, 0, static_cast<GLint>(k));
    glClearNamedFramebufferfv(s.shadow_framebuffer, GL_DEPTH, 0, &far_depth);
    glUniformMatrix4fv(s.shadow_program.uniform("light_projection"), 1, GL_FALSE, glm::value_ptr(s.light_projection[k]));
    glDrawElements(GL_TRIANGLES, index_count_, GL_UNSIGNED_INT, nullptr);
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  // Each tile's least and greatest depth, for the exact early-outs of sun_light.glsl.
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
  glUseProgram(s.minmax_program.id());
  glBindTextureUnit(kShadowUnit, s.shadow_texture);
  glBindImageTexture(0, s.tile_texture, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RG32F);
  glUniform1i(s.minmax_program.uniform("shadow_tile"), kShadowTile);
  glDispatchCompute(kTiles / 8, kTiles / 8, static_cast<GLuint>(s.discs.size()));
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
  check_gl("drawing shadow maps");
}

// Depth-only draw of the mesh with the frame's model-view-projection, then depth test LEQUAL (rewriting
// the same depth): the SUN fragment stage that follows (the shadow-map lookups) runs once per covered
// pixel, on the nearest surface only, instead of once per rasterised fragment (overdraw). shadow.vert and the
// SUN vertex stages declare gl_Position invariant, so both draws give each pixel the same depth.
void Renderer::draw_sun_prepass() {
  SunPass& s = *sun_;
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  glUseProgram(s.shadow_program.id());
  glUniformMatrix4fv(s.shadow_program.uniform("light_projection"), 1, GL_FALSE, glm::value_ptr(model_view_projection_));
  glBindVertexArray(mesh_vao_);
  glDrawElements(GL_TRIANGLES, index_count_, GL_UNSIGNED_INT, nullptr);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDepthFunc(GL_LEQUAL);
}

// The deferred pass's mesh data as buffer textures (cheaper per-pixel reads than storage buffers on
// llvmpipe): per triangle its corner indices (RGBA32UI), per vertex of transfer `transfer` three texels
// (RGBA32F) position, normal, albedo; made on first use from the GL buffers.
void Renderer::bind_sun_surface(int transfer) {
  SunPass& s = *sun_;
  SunPass::PerTransfer& t = s.transfers[static_cast<std::size_t>(transfer)];
  if (s.triangle_texture == 0) {
    const std::vector<std::uint32_t> indices = read_buffer<std::uint32_t>(indices_, static_cast<std::size_t>(index_count_));
    std::vector<glm::uvec4> packed(indices.size() / 3);
    for (std::size_t i = 0; i < packed.size(); ++i) packed[i] = glm::uvec4(indices[3 * i], indices[3 * i + 1], indices[3 * i + 2], 0u);
    buffer_texture(packed.data(), packed.size() * sizeof(glm::uvec4), GL_RGBA32UI, s.triangle_buffer, s.triangle_texture);
  }
  if (t.surface_texture == 0) {
    const std::vector<glm::vec3> positions = read_buffer<glm::vec3>(positions_, vertex_count_);
    const std::vector<glm::vec3> normals = read_buffer<glm::vec3>(normals_, vertex_count_);
    const std::vector<glm::vec3> albedo = read_buffer<glm::vec3>(t.albedo != 0 ? t.albedo : albedo_, vertex_count_);
    std::vector<glm::vec4> packed(3 * vertex_count_);
    for (std::size_t v = 0; v < vertex_count_; ++v) {
      packed[3 * v] = glm::vec4(positions[v], 0.0f);
      packed[3 * v + 1] = glm::vec4(normals[v], 0.0f);
      packed[3 * v + 2] = glm::vec4(albedo[v], 0.0f);
    }
    buffer_texture(packed.data(), packed.size() * sizeof(glm::vec4), GL_RGBA32F, t.surface_buffer, t.surface_texture);
  }
  glBindTextureUnit(kTriangleCornersUnit, s.triangle_texture);
  glBindTextureUnit(kSurfaceUnit, t.surface_texture);
}

// The discs' direct light for diffuse transfer, deferred: after the mesh draw (prt_diffuse.vert with
// SUN: sky and bounce light, unclamped, and the triangle index per pixel), one full-viewport draw at
// the far plane with the depth test GREATER reaches each covered pixel exactly once (prt_sun.frag),
// reads that pixel's radiance and triangle, and writes the clamped sum. Attachment 1 is not written
// in it; each pixel of attachment 0 is read and written by its own fragment only (the texture barrier
// makes the mesh draw's writes visible to it).
void Renderer::draw_sun_deferred(const FrameSettings& settings) {
  SunPass& s = *sun_;
  const Program& program = s.deferred_program;
  glTextureBarrier();
  const GLenum radiance_only[2] = {GL_COLOR_ATTACHMENT0, GL_NONE};
  glNamedFramebufferDrawBuffers(framebuffer_, 2, radiance_only);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_GREATER);
  glDepthMask(GL_FALSE);
  glUseProgram(program.id());
  bind_sun(program, settings, false);
  glBindTextureUnit(kFrameRadianceUnit, radiance_texture_);
  glBindTextureUnit(kFrameTriangleUnit, triangle_texture_);
  bind_sun_surface(settings.transfer);
  // Mesh coordinates: p = c + R^T (world - c) (renderer.h); ray direction R^T C (ndc.x tan_x, ndc.y tan_y, -1).
  const glm::dmat3 to_object = glm::transpose(settings.object_rotation);
  const glm::dvec3 eye = view_.centre + to_object * (view_.eye - view_.centre);
  glm::dmat3 basis = to_object * view_.camera_to_world;
  basis[0] *= view_.tan_half_fov_x;
  basis[1] *= view_.tan_half_fov_y;
  basis[2] *= -1.0;
  const glm::mat3 ray_basis(basis);
  glUniform2f(program.uniform("frame_size"), static_cast<float>(width_), static_cast<float>(height_));
  glUniform3f(program.uniform("eye_object"), static_cast<float>(eye.x), static_cast<float>(eye.y), static_cast<float>(eye.z));
  glUniformMatrix3fv(program.uniform("ray_basis"), 1, GL_FALSE, glm::value_ptr(ray_basis));
  glBindVertexArray(empty_vao_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  const GLenum both[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  glNamedFramebufferDrawBuffers(framebuffer_, 2, both);
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LESS);
}

// The discs' bounce light for the current transfer: T_bounce . L_discs per vertex (diffuse, on the CPU)
// or B (M_bounce L_discs) per vertex (glossy, prt_glossy.comp), L_discs in the object frame.
void Renderer::update_bounce(const FrameSettings& settings, int bands) {
  SunPass& s = *sun_;
  SunPass::PerTransfer& t = s.transfers[static_cast<std::size_t>(settings.transfer)];
  const int count = bands * bands;
  const glm::mat3 rotation(glm::transpose(settings.object_rotation) * settings.environment_rotation);
  std::vector<glm::vec3> rotated(static_cast<std::size_t>(count));
  sh::rotate_rgb(bands, rotation, s.disc_lighting.data(), rotated.data());
  const bool has_bounce = t.glossy ? t.bounce_gpu != nullptr : !t.bounce_cpu.values.empty();
  if (t.interreflected && !has_bounce && !t.warned) {
    std::fprintf(stderr, "prt: %s: no bounce-only section (a version 1 file): the discs' interreflected light is left out; re-bake for it\n",
                 t.origin.c_str());
    t.warned = true;
  }
  if (!t.glossy) {
    std::vector<glm::vec3> bounce(vertex_count_, glm::vec3(0.0f));
    if (has_bounce) {
      sh::RgbCoefficients lighting(bands);
      for (int i = 0; i < count; ++i) lighting.values[static_cast<std::size_t>(i)] = glm::dvec3(rotated[static_cast<std::size_t>(i)]);
      bounce = shade::shade_diffuse(t.bounce_cpu, lighting);
    }
    if (s.bounce_vertex == 0) s.bounce_vertex = dynamic_buffer(vertex_count_ * sizeof(glm::vec3));
    glNamedBufferSubData(s.bounce_vertex, 0, static_cast<GLsizeiptr>(bounce.size() * sizeof(glm::vec3)), bounce.data());
    return;
  }
  const transfer::Header& header = transfers_[static_cast<std::size_t>(settings.transfer)]->header();
  const int out_count = static_cast<int>(header.bands_out * header.bands_out);
  const std::size_t bytes = vertex_count_ * static_cast<std::size_t>(out_count) * sizeof(glm::vec4);
  if (s.bounce_outgoing == 0 || s.bounce_outgoing_bytes < bytes) {
    release(s.bounce_outgoing);
    s.bounce_outgoing = dynamic_buffer(bytes);
    s.bounce_outgoing_bytes = bytes;
  }
  if (!has_bounce) {
    const float zero = 0.0f;
    glClearNamedBufferData(s.bounce_outgoing, GL_R32F, GL_RED, GL_FLOAT, &zero);
    return;
  }
  std::vector<glm::vec4> upload(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) upload[static_cast<std::size_t>(i)] = glm::vec4(rotated[static_cast<std::size_t>(i)], 0.0f);
  glNamedBufferSubData(s.disc_lighting_buffer, 0, static_cast<GLsizeiptr>(upload.size() * sizeof(glm::vec4)), upload.data());
  const Program& compute = glossy_compute_program(static_cast<int>(header.channels), static_cast<int>(header.bands * header.bands),
                                                  count, out_count, t.bounce_gpu->chunks());
  glUseProgram(compute.id());
  t.bounce_gpu->bind();
  glUniform1i(compute.uniform("vertices_per_chunk"), static_cast<GLint>(t.bounce_gpu->vertices_per_chunk()));
  glUniform1i(compute.uniform("vertex_count"), static_cast<GLint>(vertex_count_));
  glBindBufferBase(GL_UNIFORM_BUFFER, kLightingBinding, s.disc_lighting_buffer);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBrdfBinding, brdf_buffers_[static_cast<std::size_t>(settings.transfer)]);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kOutgoingBinding, s.bounce_outgoing);
  glDispatchCompute(static_cast<GLuint>((vertex_count_ + kWorkgroupSize - 1) / kWorkgroupSize), 1, 1);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  check_gl("computing the discs' bounce light");
}

void Renderer::bind_sun_bounce() { glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBounceOutgoingBinding, sun_->bounce_outgoing); }

void Renderer::bind_sun(const Program& program, const FrameSettings& settings, bool glossy) {
  SunPass& s = *sun_;
  const SunPass::PerTransfer& t = s.transfers[static_cast<std::size_t>(settings.transfer)];
  const int n = static_cast<int>(s.discs.size());
  glm::vec3 irradiance[kMaxDiscs];
  float tan_radius[kMaxDiscs];
  for (int k = 0; k < n; ++k) {
    irradiance[k] = glm::vec3(s.discs[static_cast<std::size_t>(k)].irradiance);
    tan_radius[k] = static_cast<float>(std::tan(s.discs[static_cast<std::size_t>(k)].angular_radius));
  }
  glUniform1i(program.uniform("disc_count"), n);
  glUniform3fv(program.uniform("disc_direction"), n, glm::value_ptr(s.direction[0]));
  glUniform3fv(program.uniform("disc_irradiance"), n, glm::value_ptr(irradiance[0]));
  glUniform1fv(program.uniform("disc_tan_radius"), n, tan_radius);
  glUniformMatrix4fv(program.uniform("shadow_matrix"), n, GL_FALSE, glm::value_ptr(s.shadow_matrix[0]));
  glUniform1fv(program.uniform("shadow_depth_scale"), n, s.depth_scale.data());
  glUniform1fv(program.uniform("shadow_texel"), n, s.texel.data());
  glUniform1i(program.uniform("disc_shadows"), t.shadows ? 1 : 0);
  glBindTextureUnit(kShadowUnit, s.shadow_texture);
  glBindTextureUnit(kTileUnit, s.tile_texture);
  glUniform1i(program.uniform("shadow_tile"), kShadowTile);
  glUniform1i(program.uniform("filter_count"), kFilterCount);
  if (glossy) {
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
  } else {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kSunAlbedoBinding, t.albedo != 0 ? t.albedo : albedo_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kSunBounceBinding, s.bounce_vertex);
  }
}

std::vector<float> Renderer::shadow_visibility(const FrameSettings& settings, int disc) {
  if (!has_mesh_) fail("renderer: no mesh");
  if (disc < 0 || disc >= disc_count()) fail("renderer: no disc " + std::to_string(disc));
  transfer_header(settings.transfer);
  update_sun(settings, static_cast<int>(transfer_header(settings.transfer).bands));
  SunPass& s = *sun_;
  const Program& program = s.visibility_program;
  glUseProgram(program.id());
  bind_sun(program, settings, false);
  glUniform1i(program.uniform("disc_shadows"), 1);
  glUniform1i(program.uniform("vertex_count"), static_cast<GLint>(vertex_count_));
  glUniform1i(program.uniform("disc"), disc);
  GLuint output = dynamic_buffer(vertex_count_ * sizeof(float));
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPositionsBinding, positions_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kNormalsBinding, normals_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kSunAlbedoBinding, output);
  glDispatchCompute(static_cast<GLuint>((vertex_count_ + kWorkgroupSize - 1) / kWorkgroupSize), 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::vector<float> out(vertex_count_);
  glGetNamedBufferSubData(output, 0, static_cast<GLsizeiptr>(out.size() * sizeof(float)), out.data());
  release(output);
  check_gl("measuring shadow-map visibility");
  return out;
}

}  // namespace prt::render
