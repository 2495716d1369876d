#pragma once
// Internal to prt_bake (and the lightmap baker, src/lightmap): the passes of a diffuse bake. All
// buffers are point-major; "geometric" transfer has no albedo (bands^2 floats per point), "channel"
// transfer has `channels` blocks of bands^2 floats per point (docs/formats.md payload layout). The
// points are the mesh's vertices, or (PassContext::points) the texel sample points of a lightmap.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "bake/bake.h"
#include "bake/vertex_samples.h"
#include "core/progress.h"
#include "dist/exchange.h"
#include "mesh/mesh.h"
#include "mesh/texture.h"
#include "trace/scene.h"
#include "trace/vertex_rays.h"

namespace prt::bake {

/// Surface sample points other than the mesh's vertices: unit normals, one per position, and the unit
/// geometric normal of the triangle each lies on (the true-surface rule, trace/true_surface.h; null:
/// no rule).
struct SamplePoints {
  const std::vector<glm::vec3>* positions = nullptr;
  const std::vector<glm::vec3>* normals = nullptr;
  const std::vector<glm::vec3>* geometric_normals = nullptr;
};

/// Where a bounce pass reads the previous pass's transfer at a hit: a texel grid over the mesh's
/// lightmap UVs, filtered bilinearly (texel centres at ((i + 0.5)/W, (j + 0.5)/H), clamped to the
/// edge; texels of weight-0 coverage (kTexelEmpty) are left out and the other weights renormalised).
/// Mixed scenes (lightmap/part_choice.h): hits on a triangle that `vertex_triangle` marks 1 read the
/// previous pass per vertex instead (barycentrically, as without a grid), the block of vertex v at
/// width x height + v, after the grid's blocks.
struct TexelGrid {
  const std::vector<glm::vec2>* corner_uv = nullptr;     ///< mesh.lightmap_uv
  const std::vector<std::uint8_t>* coverage = nullptr;   ///< width x height, transfer::Coverage
  int width = 0, height = 0;
  const std::vector<std::uint8_t>* vertex_triangle = nullptr;  ///< per triangle, 1: read per vertex; null: none
  /// True if a hit on `triangle` reads the previous pass per vertex.
  bool per_vertex(std::size_t triangle) const { return vertex_triangle && (*vertex_triangle)[triangle]; }
  /// The first vertex block's index: width x height.
  std::uint32_t vertex_base() const { return static_cast<std::uint32_t>(width) * static_cast<std::uint32_t>(height); }
};

/// What every ray-tracing pass shares.
struct PassContext {
  const mesh::Mesh* mesh = nullptr;
  const trace::Scene* scene = nullptr;
  const LocalSampleSet* samples = nullptr;
  const std::vector<std::uint32_t>* order = nullptr;  ///< vertex visiting order (Morton)
  std::uint32_t seed = 0;
  int threads = 0;
  bool progress = false;
  SamplePoints points{};         ///< null members: the mesh's vertices
  const TexelGrid* grid = nullptr;  ///< null: bounce passes gather per vertex (barycentric)
  const dist::Context* dist = nullptr;  ///< the job's ranks; each traces its share of `order`
  const mesh::VertexFootprints* footprints = nullptr;  ///< null: rays leave from the vertices themselves
  bool unturned_frames = false;  ///< every point's sample frame unturned (trace::VertexRays); false: hashed turns
  /// With `points` and `footprints`: points from this one on are the mesh's vertices (a mixed scene's,
  /// trace::VertexRays::footprint_first); their rays leave from their footprints.
  std::size_t footprint_first = static_cast<std::size_t>(-1);
  /// Per point: which of samples->sets sets it traces (LocalSampleSet); null: set 0 (samples->sets 1).
  const std::vector<std::uint8_t>* point_set = nullptr;

  /// The per-point ray loop of this context (trace/vertex_rays.h) with query `query`, over this
  /// rank's share of the order.
  trace::VertexRays rays(trace::Query query) const {
    const dist::Range share = dist::my_range(dist::or_single(dist), order->size());
    return trace::VertexRays{scene, mesh, order, &samples->directions, seed, threads, query, points.positions, points.normals,
                             share.begin, share.end, footprints, points.geometric_normals, unturned_frames, footprint_first,
                             point_set, static_cast<std::size_t>(samples->sets)};
  }
  const std::vector<glm::vec3>& point_normals() const { return points.normals ? *points.normals : mesh->normals; }
  std::size_t point_count() const { return points.positions ? points.positions->size() : mesh->positions.size(); }
  /// What the loop calls a point in its progress bar.
  const char* point_unit() const { return points.positions ? "texels" : "vertices"; }
  /// The first of point v's directions in samples->directions (and rows in samples->basis).
  std::size_t first_sample(std::uint32_t v) const { return point_set ? (*point_set)[v] * samples->per_point() : 0; }
};

/// (1/pi) A_l, l < bands: the clamped-cosine factors of the unshadowed transfer.
std::vector<double> unshadowed_factors(int bands);

/// (1/pi) A_l Y_lm(n) at one unit normal: the albedo-free unshadowed transfer (bands^2 floats).
void unshadowed_vertex(int bands, const std::vector<double>& factors, const glm::vec3& normal, float* out);

/// The albedo-free unshadowed transfer at every normal (a mesh's vertices, or sample points), closed form.
void unshadowed_geometric(const std::vector<glm::vec3>& normals, int bands, int threads, std::vector<float>& out);

/// The albedo-free shadowed transfer of every vertex with the control-variate estimator (bake.h).
/// Returns the number of rays traced.
std::uint64_t shadowed_geometric(const PassContext& ctx, std::vector<float>& out);

/// True if the bounce passes take the albedo of the surface a ray hits from the base colour at the hit
/// point (mesh::TriangleColour), not from the hit vertices' albedo: meshes with base-colour textures
/// (docs/conventions.md, "Albedo and textures"). Other meshes keep the vertex rule below.
bool albedo_at_hits(const mesh::Mesh& mesh);

/// The width of the surface a bounce sample stands for, per unit of hit distance: each of a point's S
/// hemisphere samples stands for a solid angle of about 2 pi / S, a cone that at distance t covers a
/// disc of width t sqrt(2 pi / S) seen head-on (Akenine-Moller et al., "Texture Level of Detail
/// Strategies for Real-Time Ray Tracing", Ray Tracing Gems, 2019). Not divided by the cosine of
/// incidence: the disc's narrow axis, so a hit's base colour (mesh::TriangleColour::level_for) is never
/// filtered beyond the sample's footprint.
double sample_cone_width(std::size_t samples);

/// The base colour lookups of a bake's bounce hits, set up once per bake rather than once per pass or
/// hit: the mip pyramids of the mesh's textures (mesh::build_mips) and every triangle's
/// mesh::TriangleColour reading them; empty unless albedo_at_hits(*ctx.mesh). Triangles and textures in
/// parallel on ctx.threads, each entry written by one thread. Holds pointers into *ctx.mesh.
class HitColours {
 public:
  explicit HitColours(const PassContext& ctx);
  const std::vector<mesh::TriangleColour>& triangles() const { return triangles_; }

 private:
  mesh::MeshMips mips_;  // heap-allocated pyramids: triangles_ points at them, moves keep them in place
  std::vector<mesh::TriangleColour> triangles_;
};

/// One interreflection pass. Vertex rule: next[v] = albedo_v / S * sum over front-face hits of prev
/// interpolated at the hit (barycentrically over the hit triangle's vertices, or bilinearly in
/// ctx.grid), prev being the previous pass's channel transfer. With albedo_at_hits(*ctx.mesh):
/// next[v] = 1 / S * sum over front-face hits q of rho(q) * prev interpolated at q, rho(q) the base
/// colour at q averaged over the sample's footprint (TriangleColour::level_for(t sample_cone_width(S)),
/// t the hit distance: the texture's box-filtered mip level whose texels fit in the footprint, level 0
/// where the footprint spans under 2 texels), prev and next albedo-free (the receiver's albedo is not applied). `albedo` has one
/// entry per point; `channels` is 1 (grey: red values are used) or 3. `prev` has a block per vertex
/// (per texel of ctx.grid); `next` gets one per point. `hit_colours` made from ctx. Returns the number
/// of rays traced.
std::uint64_t bounce_pass(const PassContext& ctx, const HitColours& hit_colours, const std::vector<glm::vec3>& albedo, int channels,
                          const std::vector<float>& prev, std::vector<float>& next, const char* label);

/// Shared by the vertex and the texel (src/lightmap) bakes.
/// True if every albedo is grey (r = g = b).
bool all_grey(const std::vector<glm::vec3>& albedo);

/// The transfer's channel count: 1 when every albedo in `albedo` (the bake's per-vertex albedo) is grey
/// and the mesh has no base-colour texture, else 3. A textured mesh always has 3: its texels and the
/// points its rays hit take the texture's colour, whatever the vertices' averages.
int transfer_channels(const mesh::Mesh& mesh, const std::vector<glm::vec3>& albedo);

/// Channel transfer from albedo-free transfer: `channels` (1: albedo.r folded in; 3: one block per
/// channel) blocks of n floats per point. `geometric` is consumed.
std::vector<float> apply_albedo(std::vector<float>&& geometric, const std::vector<glm::vec3>& albedo, int channels, std::size_t n);

/// A pass's energy: the sum over points and channels of the l = 0 coefficient (bake.h).
double pass_energy(const std::vector<float>& values, std::size_t point_stride, std::size_t channel_stride, int channels);

/// Turns a bounce pass's per-point result `next` into the `prev` buffer the following pass gathers
/// from (vertex bakes: the same buffer, swapped; texel bakes: scattered into the texel grid and dilated).
using PrevFromNext = std::function<void(std::vector<float>& next, std::vector<float>& prev)>;

/// What the first bounce pass gathers from when albedo_at_hits: the albedo-free transfer `geometric`
/// (n floats per point) repeated in `channels` blocks per point.
std::vector<float> albedo_free_channels(const std::vector<float>& geometric, int channels, std::size_t n);

/// The interreflection passes after the direct pass (bounce rule of BakeOptions::bounces):
/// `values` (per point, the direct pass) gains every pass; `bounce_only` (resized) receives their sum
/// alone. `prev` starts as what the first pass gathers from: the direct pass's channel transfer, or
/// with albedo_at_hits its albedo-free transfer (albedo_free_channels); then each pass's result,
/// albedo-free, gets `albedo` (the receivers') folded in before it is added. Fills rep's bounces_done, pass_energy
/// (after the direct pass's entry) and rays_traced.
void interreflect(const PassContext& ctx, const std::vector<glm::vec3>& albedo, int channels, const BakeOptions& options,
                  std::vector<float> prev, const PrevFromNext& prev_from_next, std::vector<float>& values,
                  std::vector<float>& bounce_only, BakeReport& rep);

/// Before the bounce passes: replaces `scene` (the direct pass's, built with bake_scene_options, without
/// robust mode) by a robust scene of the same mesh, freeing the first BVH before building the second:
/// the bounce passes trace only closest hits, which trace/vertex_rays.h always traces robust, so a scene
/// without robust mode would otherwise build its robust BVH beside its own. Adds the build time to
/// `build_seconds`. The answers are those of the lazily built robust BVH (the same deterministic build).
void use_robust_scene(std::unique_ptr<trace::Scene>& scene, const mesh::Mesh& mesh, int threads, double& build_seconds);

/// The bake parameters block of a diffuse transfer file (JSON object text).
std::string parameters_json(const BakeOptions& options, const mesh::Mesh& mesh, int bounces_done, float ray_offset);

}  // namespace prt::bake
