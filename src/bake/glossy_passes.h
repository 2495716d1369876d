#pragma once
// Internal to prt_bake: the passes of a glossy bake (bake.h, GLOSSY). Buffers are vertex-major; a
// "matrix" is bands_out^2 x bands^2 floats, row-major [out][in]; "channel" buffers hold `channels`
// matrices per vertex.
#include <cstdint>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "bake/bake.h"
#include "bake/vertex_samples.h"
#include "brdf/projection.h"
#include "brdf/vertex_brdfs.h"
#include "dist/exchange.h"
#include "mesh/mesh.h"
#include "sh/rotation.h"
#include "trace/scene.h"
#include "trace/vertex_rays.h"

namespace prt::bake {

/// What every glossy pass shares.
struct GlossyContext {
  const mesh::Mesh* mesh = nullptr;
  const trace::Scene* scene = nullptr;
  const LocalSampleSet* samples = nullptr;            ///< uniform hemisphere directions, basis of `bands` bands
  const std::vector<std::uint32_t>* order = nullptr;  ///< vertex visiting order (Morton)
  const std::vector<glm::mat3>* frames = nullptr;     ///< brdf::shading_frame of every vertex normal
  int bands = 0;                                      ///< lighting (input) bands
  int bands_out = 0;                                  ///< transferred-radiance (output) bands
  std::uint32_t seed = 0;
  int threads = 0;
  bool progress = false;
  const dist::Context* dist = nullptr;  ///< the job's ranks; each traces its share of `order`
  const mesh::VertexFootprints* footprints = nullptr;  ///< null: rays leave from the vertices themselves

  /// The per-vertex ray loop of this context (trace/vertex_rays.h) with query `query`, over this
  /// rank's share of the order.
  trace::VertexRays rays(trace::Query query) const {
    const dist::Range share = dist::my_range(dist::or_single(dist), order->size());
    return trace::VertexRays{scene, mesh, order, &samples->directions, seed, threads, query, nullptr, nullptr, share.begin, share.end, footprints};
  }
};

/// The glossy half of bake() (bake.h, GLOSSY); options already validated.
transfer::TransferData bake_glossy(const mesh::Mesh& mesh, const BakeOptions& options, BakeReport* report);

/// The direct (shadowed) pass: per vertex M = Rot(F^T) - (2 pi / S) Rot_out(F^T F_s) C Rot_in(F_s^T),
/// C = sum over occluded samples of y_out(w_s) y_in(w_s)^T (bake.h, GLOSSY). One channel. Returns the
/// number of rays traced.
std::uint64_t glossy_direct_pass(const GlossyContext& ctx, std::vector<float>& out);

/// One interreflection pass. `prev` holds the previous pass's matrices (`channels` per vertex); the
/// radiance leaving a hit corner q toward the gathering vertex is sum_k (B_q,c prev_q,c)_k Y_k(F_q^T (-w)).
/// Corner q's BRDF matrix is brdf_matrices[brdfs.of(q)] (one per entry of brdfs.table), each with
/// bands_out bands and 1 or `channels` channels. Returns the number of rays traced.
std::uint64_t glossy_bounce_pass(const GlossyContext& ctx, const std::vector<brdf::BrdfMatrix>& brdf_matrices,
                                 const brdf::VertexBrdfs& brdfs, int channels,
                                 const std::vector<float>& prev, std::vector<float>& next, const char* label);

/// matrix (rows x r.bands()^2, row-major) := matrix Rot(r)^T, i.e. every row replaced by r applied to it.
void rotate_rows(const sh::Rotation& r, int rows, double* matrix);
/// matrix (r.bands()^2 x columns, row-major) := Rot(r) matrix, restricted to its first rows: every
/// column replaced by r applied to it. r.bands()^2 rows.
void rotate_columns(const sh::Rotation& r, int columns, double* matrix);

}  // namespace prt::bake
