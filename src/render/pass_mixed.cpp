// A mixed scene's pass (transfer_pass.h make_mixed_pass; renderer.h, PASSES: mixed; docs/conventions.md
// "Mixed scenes"): a lightmap pass and a per-vertex pass sharing one frame and one depth buffer, each
// drawing its own runs of triangles.
//
// Order: the per-vertex diffuse pass adds the discs' direct light in a deferred pass over every pixel
// the mesh covers so far (SunLight::draw_deferred), so it draws first, when the pixels covered are its
// own; the lightmap pass shades the discs in its own fragments and draws second, over the same depth
// buffer (GL_LESS): where a texel triangle is nearer it replaces the pixel, elsewhere the per-vertex
// pixel stays. Each pixel is then that of its nearest triangle, computed as the pass of that triangle's
// kind computes it on a whole frame of its own.
#include <string>

#include "core/error.h"
#include "render/transfer_pass.h"

namespace prt::render {

namespace {

class MixedPass final : public TransferPass {
 public:
  MixedPass(TransferPass& texel, TransferPass& vertex, TriangleRuns texel_runs, TriangleRuns vertex_runs)
      : TransferPass(texel.sun_surface().origin, texel.header().kind),
        texel_(texel),
        vertex_(vertex),
        texel_runs_(std::move(texel_runs)),
        vertex_runs_(std::move(vertex_runs)) {}

  const transfer::Header& header() const override { return texel_.header(); }
  const char* name() const override { return "mixed"; }

  void prepare_sun(FrameCore& core, const Frame& frame) override {
    vertex_.prepare_sun(core, frame);
    texel_.prepare_sun(core, frame);
  }

  void draw(FrameCore& core, const Frame& frame) override {
    Frame share = frame;
    share.triangles = &vertex_runs_;
    vertex_.draw(core, share);
    share.triangles = &texel_runs_;
    texel_.draw(core, share);
  }

  void set_surface_albedo(const std::vector<glm::vec3>& albedo) override {
    texel_.set_surface_albedo(albedo);
    vertex_.set_surface_albedo(albedo);
  }
  void set_textured(bool textured) override {
    texel_.set_textured(textured);
    vertex_.set_textured(textured);
  }

 private:
  TransferPass& texel_;
  TransferPass& vertex_;
  TriangleRuns texel_runs_, vertex_runs_;
};

void check_runs(const TriangleRuns& runs, std::uint64_t triangle_count, const std::string& origin) {
  std::uint64_t next = 0;
  for (const auto& [first, count] : runs) {
    if (first < next || count > triangle_count || first > triangle_count - count)
      fail_file(origin, "mixed scene: the per-vertex triangle runs are not increasing, disjoint runs inside the mesh's " +
                            std::to_string(triangle_count) + " triangles");
    next = first + count;
  }
}

}  // namespace

std::unique_ptr<TransferPass> make_mixed_pass(const FrameCore& core, TransferPass& texel, TransferPass& vertex,
                                              const TriangleRuns& vertex_runs) {
  const std::string& origin = texel.sun_surface().origin;
  if (!texel.header().is_texel() || !texel.draws_runs() || texel.deferred_sun())
    fail_file(origin, std::string("mixed scene: the texel share must be an uncompressed lightmap, not ") + texel.name());
  if (vertex.header().is_texel() || !vertex.draws_runs())
    fail_file(vertex.sun_surface().origin,
              std::string("mixed scene: the per-vertex share must be uncompressed diffuse per-vertex transfer, not ") + vertex.name());
  if (vertex.header().bands != texel.header().bands)
    fail_file(vertex.sun_surface().origin, "mixed scene: " + std::to_string(vertex.header().bands) + " bands, its partner " +
                                               origin + " " + std::to_string(texel.header().bands));
  const std::uint64_t triangles = static_cast<std::uint64_t>(core.index_count) / 3;
  check_runs(vertex_runs, triangles, origin);
  return std::make_unique<MixedPass>(texel, vertex, complement_runs(vertex_runs, triangles), vertex_runs);
}

}  // namespace prt::render
