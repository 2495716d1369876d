#pragma once
// The real-time relighting renderer, shared by the window (prt view) and headless (prt render) paths.
// Everything here needs a current OpenGL 4.5 core context (HeadlessContext, or a GLFW window's).
//
// STRUCTURE: one frame core (frame_core.h: the mesh, the lighting, the camera, the framebuffer, the
// background, the tone map, and the sun's discs and shadow maps, sun_light.h) and one pass per transfer
// kind behind one interface (transfer_pass.h: pass_diffuse.cpp, pass_glossy.cpp, pass_cpca.cpp,
// pass_lightmap.cpp), each owning its transfer on the GPU and how the discs light it. render() draws
// the core's background and then the pass of the frame's transfer; it never names a kind.
//
// PASSES (shaders/ names; see shader_program.h for how sources are found):
//   background  fullscreen.vert + background.frag: the environment behind the mesh, per pixel along the
//               view direction: the equirect image (bilinear, as Environment::radiance), its SH
//               reconstruction (the first k bands, as prt::sh::eval), or black; the first two with the
//               discs the frame shades drawn over them (uniform radiance L = E / (pi sin^2 a) inside the
//               angular radius, the rim pixels weighted by how much of them it covers; a second draw with
//               DISCS over each disc's screen rectangle, camera::cap_pixel_rect), so that the sky behind
//               the mesh is the lighting it is shaded with (load_render_lighting: the image without them).
//   prt_diffuse prt_diffuse.vert + surface.frag (one program per channel count, transfer bands and
//               truncation, compiled on first use): per-vertex diffuse PRT. The transfer is uploaded once
//               into a buffer, vertex-major exactly as in the file (channels x bands^2 floats per vertex),
//               read through buffer-texture views (see TransferBuffer); per frame the CPU rotates the lighting by R_object^-1 R_environment with
//               prt::sh::rotate_rgb and uploads it; the vertex shader takes, per channel, the dot product
//               of the first k^2 transfer coefficients with the lighting (prt::shade::shade_diffuse), and
//               the rasteriser interpolates that radiance (perspective-correct).
//   prt_glossy  glossy PRT, for a glossy transfer (prt::bake GLOSSY): a COMPUTE pass, prt_glossy.comp,
//               computes per frame for every vertex O_p = B (M_p L) (the transfer matrices through the
//               same buffer-texture views, the lighting in the object's frame, the BRDF matrix B from
//               set_brdf) into a storage buffer; then prt_glossy.vert + prt_glossy.frag draw the mesh and
//               each fragment evaluates, for each corner of its triangle, sum_k O_k Y_k(F^T v) in that
//               corner's local frame F (brdf::shading_frame of its normal) toward the fragment's own view
//               direction v (eye - fragment position, mesh coordinates), and blends the three with the
//               fragment's barycentrics. At a vertex this is prt::shade::shade_glossy exactly; the
//               per-corner frames avoid interpolating coefficients between different frames (the frame's
//               singularity at n = +-Y, brdf/frame.h).
//   prt_cpca    prt_cpca.comp, then prt_cpca.vert + surface.frag, for a CPCA-compressed transfer (.cprt,
//               add_compressed): the CPU multiplies each cluster's mean and PCA directions with the
//               lighting (glossy: then B), the compute pass blends them per vertex with its weights
//               (glossy: evaluated toward the eye at the vertex), the draw interpolates (renderer_cpca.h).
//   prt_lightmap prt_lightmap.vert + prt_lightmap.frag, for a texel (lightmap) transfer (add_lightmap):
//               the transfer is uploaded once as texture arrays, four values per layer; per pixel the
//               fragment shader samples them bilinearly at the lightmap UV and takes the dot product with
//               the object-frame lighting; with discs, also the bounce-only layers with the discs' SH and
//               the discs' direct light per pixel as prt_sun.frag (renderer_lightmap.h).
//   mixed       a mixed scene (add_mixed, pass_mixed.cpp): the per-vertex diffuse pass draws its runs of
//               triangles (one draw per run; first_triangle + gl_PrimitiveID is the mesh triangle index,
//               triangle_runs.h), with its deferred direct light over the pixels covered so far, then the
//               lightmap pass draws the other triangles into the same frame and depth buffer; each pixel is
//               that of its nearest triangle, shaded by that triangle's kind.
//   lambert     lambert.vert + surface.frag: a baseline without PRT, albedo * E * max(n . l, 0) for one
//               directional light (see lambert_light()).
//   sun         discs (light/disc.h: a sun, lamps; set_discs), sun_light.cpp: when the lighting
//               changes (environment or object rotation, discs, transfer, bands, BRDF) and only then,
//               within the same frame, shadow.vert draws one orthographic depth map per disc (at most
//               kMaxDiscs, kShadowMapSize^2, fitted to the mesh bounds in the object's frame), and the
//               discs' bounce light T_bounce . SH(discs) is recomputed per vertex (diffuse: on the CPU,
//               prt::shade::shade_diffuse; glossy: prt_glossy.comp on the bounce matrices into a buffer
//               that the per-frame pass adds to O). Each disc's direct light is then added per pixel,
//               its visibility filtered PCSS-style from the map (shaders/sun_light.glsl,
//               docs/conventions.md "Sun shadow maps"), and each channel clamped at 0 as prt::shade's
//               split shading does: diffuse, deferred (prt_diffuse.vert with SUN + surface.frag draw
//               the sky and bounce light, then sun_fullscreen.vert + prt_sun.frag shade each covered
//               pixel once from its triangle id); glossy, in prt_glossy.frag (SUN, the BRDF evaluated
//               exactly) after a depth-only prepass (shadow.vert). Without discs (or
//               FrameSettings::sun false) the passes are exactly those above.
//   texture     for a textured mesh (set_textured), prt_diffuse and prt_cpca of diffuse transfer with
//               TEXTURED (base_colour.h): the mesh drawn indexed over its draw vertices (one per
//               vertex, base-colour UV and material: textured_corners.h), each vertex's radiance divided by its albedo (textured_vertex.glsl) and the
//               corner's transformed base-colour UV, texture slot and factor x COLOR_0 passed on;
//               surface.frag multiplies the interpolated radiance by the base colour at the pixel
//               (base_texture.glsl); with discs, prt_sun.frag with TEXTURED takes the base colour at the
//               pixel as the direct light's albedo.
//   tonemap     fullscreen.vert + tonemap.frag: exposure, tone map and sRGB for the window, exactly
//               prt::image::to_display.
// The frame is drawn into a float framebuffer: attachment 0 RGBA32F linear radiance (alpha 1 on the
// mesh, 0 on the background), attachment 1 R32UI triangle index (kNoTriangle on the background),
// 32-bit float depth. No multisampling, so every pixel is one sample at its centre.
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "brdf/projection.h"
#include "camera/camera.h"
#include "brdf/brdf.h"
#include "brdf/vertex_brdfs.h"
#include "image/image.h"
#include "light/disc.h"
#include "mesh/mesh.h"
#include "render/gl.h"
#include "render/shader_program.h"
#include "render/triangle_runs.h"
#include "sh/coefficients.h"
#include "transfer/transfer_file.h"

namespace prt::compress {
struct CompressedTransfer;
}

namespace prt::render {

struct FrameCore;
class TransferPass;
struct Frame;

// The camera is prt::camera (src/camera, no GL), shared with `prt reference --image`; the renderer's
// API keeps its names.
using camera::Camera;
using camera::kVerticalFovDegrees;
using camera::orbit_view;
using camera::parse_camera;
using camera::parse_size;
using camera::ViewMatrices;

/// Triangle index of pixels the mesh does not cover.
inline constexpr std::uint32_t kNoTriangle = 0xFFFFFFFFu;

/// What is drawn behind the mesh.
enum class Background { black, environment, sh };
/// Parses "black", "env", "sh"; throws prt::OptionError("background", ": ...") otherwise.
Background parse_background(const std::string& name);
const char* background_name(Background background);  ///< "black", "env", "sh"

/// How the mesh is shaded.
enum class Shading { prt, lambert };

/// Most discs the renderer shades (the first ones of set_discs), and the side of each one's shadow map.
inline constexpr int kMaxDiscs = 4;
inline constexpr int kShadowMapSize = 2048;

/// Most ranges one transfer is split into (buffer textures the vertex shader samples).
inline constexpr int kMaxTransferChunks = 8;

/// A diffuse or glossy transfer on the GPU: one buffer holding the vertex-major floats exactly as
/// TransferData::values, uploaded once, read by the vertex shader through GL_R32F buffer-texture views
/// (texelFetch). Views rather than a shader storage block: on llvmpipe the 75 texelFetches of a 5-band
/// RGB vertex cost about half as much as 75 storage-buffer loads, and a view may be larger (Mesa:
/// 128 Mi texels = 512 MiB, against 128 MiB per storage block). A transfer larger than one view is viewed as up to
/// kMaxTransferChunks consecutive ranges of vertices_per_chunk() whole vertices each (offsets aligned
/// to GL_TEXTURE_BUFFER_OFFSET_ALIGNMENT); the vertex shader picks the range by vertex index.
class TransferBuffer {
 public:
  /// Uploads the values once (immutable storage) and creates the views. Throws prt::Error("<origin>:
  /// ...") if its value count does not match its header, or it needs more than
  /// kMaxTransferChunks views. `max_range_bytes` > 0 lowers the per-view limit below the
  /// implementation's (tests use it to exercise several ranges).
  TransferBuffer(const transfer::TransferData& transfer, const std::string& origin, std::size_t max_range_bytes = 0);
  ~TransferBuffer();
  TransferBuffer(const TransferBuffer&) = delete;
  TransferBuffer& operator=(const TransferBuffer&) = delete;

  const transfer::Header& header() const { return header_; }
  GLuint buffer() const { return buffer_; }
  int chunks() const { return chunks_; }
  std::size_t vertices_per_chunk() const { return vertices_per_chunk_; }
  /// Binds view k to texture unit k, for k < chunks().
  void bind() const;

 private:
  transfer::Header header_;
  GLuint buffer_ = 0;
  std::vector<GLuint> views_;
  int chunks_ = 1;
  std::size_t vertices_per_chunk_ = 0;
};

/// Everything that can change from frame to frame.
struct FrameSettings {
  Camera camera;
  glm::dmat3 environment_rotation{1.0};  ///< active rotation of the environment (lighting and background)
  glm::dmat3 object_rotation{1.0};       ///< active rotation of the mesh about its bounds centre
  int transfer = 0;                      ///< which transfer (index returned by add_transfer)
  int bands = 0;                         ///< use the first `bands` bands; 0 = all the transfer has
  Background background = Background::environment;
  Shading shading = Shading::prt;
  bool sun = true;                       ///< shade the discs of set_discs (false: the sky alone)
};

/// The single directional light of the Lambert baseline, in the environment's frame: direction = the
/// normalised luminance-weighted band-1 vector of the lighting (where a cosine lobe collects most light;
/// +Y if band 1 is zero), radiance = the lighting's mean radiance L_0 Y_0 per channel, so that
/// E = pi * mean radiance at normal incidence, as for a uniform environment.
void lambert_light(const sh::RgbCoefficients& lighting, glm::dvec3& direction, glm::dvec3& radiance);

/// The bands a frame of a transfer with `header` uses: shade::shading_bands (the run-time truncation
/// rule, docs/conventions.md): `requested`, or all the transfer has for 0.
int used_bands(const transfer::Header& header, int requested);

class Renderer {
 public:
  /// Compiles and links every pass (prt_diffuse for 3 channels and 5 bands; other variants on first
  /// use). Throws prt::Error naming the shader file on a GLSL error.
  Renderer();
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  /// Uploads positions, normals, albedo (0.8 grey where the mesh has none) and indices; drops the
  /// transfers of a previous mesh.
  void set_mesh(const mesh::Mesh& mesh);
  /// Uploads a diffuse or glossy transfer for the current mesh (see TransferBuffer, also for
  /// max_range_bytes); returns its index. Throws prt::Error("<origin>: ...") if its vertex count differs
  /// from the mesh's. (Callers check the mesh fingerprint with transfer::check_mesh_match first.) A glossy
  /// transfer needs set_brdf before it is rendered.
  int add_transfer(const transfer::TransferData& transfer, const std::string& origin, std::size_t max_range_bytes = 0);
  /// Uploads any transfer, through the pass that draws its kind (transfer_pass.h): `transfer` (for a
  /// compressed one its header, float32, values ignored) and `compressed`, the CPCA model of a .cprt
  /// file, or null. add_transfer, add_compressed and add_lightmap are this. Returns its index.
  int add(const transfer::TransferData& transfer, const compress::CompressedTransfer* compressed, const std::string& origin,
          std::size_t max_range_bytes = 0);
  /// Uploads the BRDF matrix a glossy transfer is shaded with (replacing the previous one: live BRDF
  /// edits re-project B on the CPU and call this). Throws prt::Error unless `transfer` is a glossy
  /// transfer's index and matrix.bands equals its bands_out.
  void set_brdf(int transfer, const brdf::BrdfMatrix& matrix);
  /// The same, and the BRDF itself, which the discs' direct light evaluates exactly (at most 8
  /// brdf::terms). A glossy transfer needs this form before it is rendered with discs.
  void set_brdf(int transfer, const brdf::BrdfMatrix& matrix, const brdf::Brdf& surface);
  /// One BRDF per vertex (a `--brdf mesh` bake, shade::baked_brdfs): vertex v is shaded with
  /// brdfs.table[brdfs.of(v)], projected here to the transfer's output bands; the discs' direct light
  /// evaluates each corner's BRDF exactly and blends the values with the fragment's barycentrics. A
  /// table of one is set_brdf with it. Throws prt::Error unless `transfer` is a per-vertex glossy
  /// transfer's index (a compressed one takes one BRDF), brdfs.vertex is empty or has one index below
  /// the table's size per vertex, and each BRDF has at most 8 brdf::terms.
  void set_brdfs(int transfer, const brdf::VertexBrdfs& brdfs);
  /// The per-vertex albedo the discs' diffuse direct light uses for transfer `transfer`
  /// (shade::surface_albedo: the albedo it was baked with). Until set: the mesh's albedo (0.8 grey
  /// where it has none). Throws prt::Error for a wrong size or index.
  void set_surface_albedo(int transfer, const std::vector<glm::vec3>& albedo);
  /// Shows the mesh's base colour per pixel for transfer `transfer` (PASSES: texture; the albedo split,
  /// docs/conventions.md "Albedo and textures"): for a transfer baked with the mesh's albedo
  /// (Mesh::albedo) on a textured mesh. The per-vertex diffuse passes (prt_diffuse, prt_cpca of diffuse
  /// transfer) then divide each vertex's radiance by its albedo and multiply the interpolated value by
  /// the base colour at the pixel (with discs, their direct light too); glossy and lightmap transfer are
  /// drawn as before. Throws prt::Error for a wrong index, or `textured` on an untextured mesh.
  void set_textured(int transfer, bool textured);
  /// Uploads a CPCA-compressed transfer (renderer_cpca.h; a texel model: pass_lightmap_cpca.cpp, drawn
  /// compressed, is_lightmap true) for the current mesh; returns its index in the same list as
  /// add_transfer. Throws prt::Error("<origin>: ...") if its vertex count differs.
  int add_compressed(const compress::CompressedTransfer& compressed, const std::string& origin);
  bool is_compressed(int transfer) const;  ///< a per-vertex CPCA transfer
  /// Uploads a texel (lightmap) transfer (transfer::Header::is_texel; diffuse kinds) for the current
  /// mesh, which must have lightmap UVs (renderer_lightmap.h); returns its index in the same list as
  /// add_transfer. Throws prt::Error("<origin>: ...") if its vertex count differs from the mesh's, the
  /// mesh has no lightmap UVs or the textures exceed the OpenGL limits. (Callers check the mesh and UV
  /// fingerprints first.)
  int add_lightmap(const transfer::TransferData& transfer, const std::string& origin);
  bool is_lightmap(int transfer) const;
  /// A mixed scene (docs/conventions.md "Mixed scenes"): a new transfer index whose frames draw, in one
  /// frame with one depth buffer, the triangles `vertex_runs` (runs [first, first + count) of mesh
  /// triangles, increasing and disjoint) with per-vertex transfer `vertex` and every other triangle with
  /// lightmap transfer `texel` (PASSES: mixed). Each keeps its own settings (set_surface_albedo,
  /// set_textured on their own indices, or on this one for both); both stay in the list as they are.
  /// Throws prt::Error unless `texel` is an uncompressed lightmap, `vertex` an uncompressed per-vertex
  /// diffuse transfer of the same bands, and the runs lie inside the mesh in order.
  int add_mixed(int texel, int vertex, const TriangleRuns& vertex_runs);
  /// Draws lightmap transfer `settings.transfer` in texel space into the float framebuffer, resized to
  /// its texel_width x texel_height: each triangle at its lightmap UV, so that read_radiance()'s pixel
  /// (i, j) is texel (i, j) shaded at its centre (as render() shades it per pixel: the rotations, bands,
  /// discs and shadow maps of `settings`; camera and background ignored). Texels no triangle's
  /// rasterisation covers stay 0 (read_triangle_ids: kNoTriangle). For tests: the GPU at texel centres.
  void render_texels(const FrameSettings& settings);
  int transfer_count() const { return static_cast<int>(passes_.size()); }
  const transfer::Header& transfer_header(int index) const;

  /// Sets the lighting: SH radiance coefficients in the environment's own frame (any bands; missing
  /// bands count as zero, as in shade_diffuse) and, optionally, the equirect image it came from (for
  /// the "env" background; nullptr if there is none, e.g. an SH lighting file).
  void set_lighting(const sh::RgbCoefficients& lighting, const image::Image* equirect);
  bool has_environment_image() const;
  /// Sets the discs (environment frame, brightest first; only the first kMaxDiscs are shaded); empty:
  /// none. Interreflected transfer without a bounce-only section leaves their bounce light out, with
  /// one warning line on stderr per transfer.
  void set_discs(const std::vector<light::Disc>& discs);
  int disc_count() const;
  /// How many times the shadow maps were drawn (each time the lighting changed, see PASSES: sun).
  int shadow_map_updates() const;
  /// Visibility of disc `disc` at every vertex as the fragment passes evaluate it from the shadow map
  /// (sun_visibility.comp), for `settings`' rotations. For tests and measurements.
  std::vector<float> shadow_visibility(const FrameSettings& settings, int disc);

  /// The per-frame CPU work of relighting: rotates the first `bands` bands of the lighting by
  /// R_object^-1 R_environment (prt::sh::rotate_rgb) and uploads them. render() calls it.
  void update_lighting(const glm::dmat3& environment_rotation, const glm::dmat3& object_rotation, int bands);

  /// Draws one frame into the float framebuffer (resized to width x height as needed). Throws
  /// prt::Error if no mesh is set, the transfer index is out of range, bands is outside
  /// [0, transfer bands], or the background is "env" without an environment image.
  void render(const FrameSettings& settings, int width, int height);

  /// The view and the model-view-projection matrix (as uploaded, float) of the last render().
  const ViewMatrices& last_view() const;
  const glm::mat4& last_model_view_projection() const;
  int width() const;
  int height() const;

  /// Linear radiance of the last frame, RGB, top row first (no exposure, no tone map).
  image::Image read_radiance() const;
  /// Triangle index per pixel of the last frame, top row first; kNoTriangle where the mesh is absent.
  std::vector<std::uint32_t> read_triangle_ids() const;

  /// Draws the last frame tone mapped into framebuffer `target` (0: the window) of the same size:
  /// 2^exposure_stops, the operator, sRGB encoding; the same maths as prt::image::to_display.
  void present(GLuint target, double exposure_stops, image::ToneMap tone_map);

 private:
  TransferPass& pass(int index) const;
  /// The object-frame lighting of the frame and, with discs, the shadow maps and the pass's share.
  void prepare(TransferPass& pass, const Frame& frame);
  std::unique_ptr<FrameCore> core_;
  std::vector<std::unique_ptr<TransferPass>> passes_;  // per transfer index
};

}  // namespace prt::render
