#pragma once
// Internal to the renderer: one pass per transfer kind (renderer.h, PASSES), behind one interface.
//
// A pass owns what belongs to its transfer on the GPU (buffers, textures, its BRDF) and how the discs
// light it (its SunSurface and, where it has one, its bounce light); everything shared by every pass --
// the mesh, the lighting, the camera, the framebuffer, the sun's shadow maps -- is the FrameCore's
// (frame_core.h), which the pass reads and binds.
//
// ADDING A TRANSFER KIND: a new file src/render/pass_<name>.cpp (picked up by src/render/CMakeLists.txt)
// that defines a TransferPass and
//   std::unique_ptr<TransferPass> make_<name>_pass(FrameCore& core, const PassInput& input);
// returning null for transfer it does not draw, and one line PASS(<name>) in transfer_pass.cpp, whose
// order says which factory is asked first. The Renderer never names a kind.
#include <memory>
#include <string>

#include "brdf/brdf.h"
#include "brdf/projection.h"
#include "compress/compressed.h"
#include "render/frame_core.h"
#include "render/sun_light.h"
#include "transfer/transfer_file.h"

namespace prt::render {

/// One transfer given to the renderer: its data (values, or for a compressed one the header only) and,
/// for a compressed (CPCA) file, its model.
struct PassInput {
  const transfer::TransferData& transfer;
  const compress::CompressedTransfer* compressed = nullptr;
  std::string origin;                  ///< the file it came from (error messages)
  std::size_t max_range_bytes = 0;     ///< see TransferBuffer
};

/// What one frame asks of a pass.
struct Frame {
  const FrameSettings& settings;
  int index = 0;             ///< the transfer's index (error messages)
  int bands = 0;             ///< bands used this frame, in [1, header().bands]
  bool sun = false;          ///< the discs are shaded this frame (the core's SunLight holds them)
  bool texel_space = false;  ///< draw in texel space (Renderer::render_texels; lightmap passes only)
  /// The triangles to draw, a share of a mixed frame (pass_mixed.cpp); null: the whole mesh. Only
  /// passes whose draws_runs() is true are given runs.
  const TriangleRuns* triangles = nullptr;
};

class TransferPass {
 public:
  virtual ~TransferPass() = default;

  /// The (uncompressed, float32) transfer's header.
  virtual const transfer::Header& header() const = 0;
  /// A name for tests and messages: "diffuse", "glossy", "cpca", "lightmap".
  virtual const char* name() const = 0;
  /// The BRDF matrix of a glossy transfer (Renderer::set_brdf checked kind and bands).
  virtual void set_brdf(const brdf::BrdfMatrix& matrix);
  /// Several BRDF matrices (equal bands) and each vertex's index into them (Renderer::set_brdfs checked
  /// kind, bands, sizes and indices). Only the per-vertex glossy pass takes them; the others throw.
  virtual void set_brdf_table(const std::vector<brdf::BrdfMatrix>& matrices, const std::vector<std::uint32_t>& vertex);
  /// Before the frame's framebuffer is bound, with the shadow maps up to date: whatever of the discs'
  /// light the pass computes when the lighting changes (its bounce light). Only on frames with discs.
  virtual void prepare_sun(FrameCore& core, const Frame& frame);
  /// Draws the mesh (frame.triangles of it) into the bound framebuffer (the background drawn, depth
  /// cleared, or the depth of an earlier share of a mixed frame kept).
  virtual void draw(FrameCore& core, const Frame& frame) = 0;
  /// Whether draw() honours Frame::triangles (the per-vertex diffuse and the lightmap passes).
  virtual bool draws_runs() const { return false; }
  /// Whether draw() adds the discs' direct light in a deferred pass over every pixel the mesh covers
  /// so far (SunLight::draw_deferred) rather than in its own fragments.
  virtual bool deferred_sun() const { return false; }
  /// Sets the albedo of the discs' direct light (Renderer::set_surface_albedo).
  virtual void set_surface_albedo(const std::vector<glm::vec3>& albedo) { sun_surface_.set_albedo(albedo); }

  /// How the discs light this transfer.
  SunSurface& sun_surface() { return sun_surface_; }
  /// Renderer::set_textured: draw albedo-free radiance per vertex and multiply it by the base colour per
  /// pixel (BaseColour::draw_corners). Only the per-vertex diffuse passes (diffuse, cpca of diffuse
  /// transfer) do; the others ignore it.
  virtual void set_textured(bool textured) { textured_ = textured; }

 protected:
  /// Sets the sun surface's origin and shadows flag (false for unshadowed transfer).
  TransferPass(const std::string& origin, transfer::Kind kind);
  SunSurface sun_surface_;
  bool textured_ = false;
  /// Prints, once per pass, that an interreflected transfer has no bounce-only section (`what`: the
  /// rest of the line).
  void warn_no_bounce(const char* what);
};

/// The pass for `input`: the first registered factory (transfer_pass.cpp) that takes it. Throws
/// prt::Error("<origin>: ...") if none does.
std::unique_ptr<TransferPass> make_pass(FrameCore& core, const PassInput& input);

/// A mixed scene's pass (pass_mixed.cpp; not in the factory list: it is made of two passes already
/// made): one frame, one depth buffer, `vertex` drawing the triangles `vertex_runs` and `texel` every
/// other triangle of the core's mesh. Both passes stay owned by the caller and must outlive it. Throws
/// prt::Error unless `texel` is a lightmap pass and `vertex` a per-vertex pass that draw runs, of the
/// same bands, and the runs are increasing, disjoint and inside the mesh.
std::unique_ptr<TransferPass> make_mixed_pass(const FrameCore& core, TransferPass& texel, TransferPass& vertex,
                                              const TriangleRuns& vertex_runs);

/// The prt_diffuse program for (channels, transfer coefficients, used coefficients, chunks, discs,
/// and for a textured draw BaseColour::defines()).
const Program& diffuse_program(FrameCore& core, int channels, int coefficient_count, int used_count, int chunks, bool sun,
                               const std::string& textured_defines = "");

/// Fails with "<origin>: transfer has N vertices, the mesh M" unless the counts match (every pass's
/// first check).
void check_vertex_count(const FrameCore& core, const transfer::Header& header, const std::string& origin, const char* what = "transfer");

}  // namespace prt::render
