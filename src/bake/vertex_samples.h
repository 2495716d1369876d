#pragma once
// The hemisphere sample set every vertex traces and per-vertex frames: internal to prt_bake.
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "trace/scene.h"

namespace prt::bake {

/// S hemisphere directions about +z (local frame) and the SH basis at each of them; or `sets` such
/// sets of S one after the other (make_interleaved_sample_sets), point v tracing set k_v's directions
/// [k_v S, (k_v + 1) S) (PassContext::point_set).
struct LocalSampleSet {
  int bands = 0;
  int sets = 1;                       ///< sets of S directions; >= 1
  std::vector<glm::vec3> directions;  ///< sets x S unit vectors, z >= 0
  std::vector<float> basis;           ///< sets x S x bands^2, sample-major: basis[s * bands^2 + i] = Y_i(directions[s])
  /// S: the directions one point traces.
  std::size_t per_point() const { return directions.size() / static_cast<std::size_t>(sets); }
};

/// A visibility worker of trace::trace_vertex_rays that sums per occluded ray (the glossy direct pass's
/// outer products): per vertex, hands the basis row of each occluded sample to
/// Derived::add_occluded(const float* y) (after Derived::clear() at the start) and remembers whether any
/// ray was occluded. Derived adds finish(v, frame). The shadowed pass sums rows with OccludedRowSums.
template <class Derived>
class OccludedSamples {
 public:
  explicit OccludedSamples(const LocalSampleSet& set) : set_(set), n_(set.bands * set.bands) {}

  void start(std::uint32_t, const glm::mat3&) {
    any_occluded_ = false;
    static_cast<Derived*>(this)->clear();
  }

  void batch(std::uint32_t, const trace::RayBatch& batch, std::size_t first) {
    for (std::size_t i = 0; i < batch.size(); ++i) {
      if (!batch.is_occluded(i)) continue;
      any_occluded_ = true;
      static_cast<Derived*>(this)->add_occluded(set_.basis.data() + (first + i) * n_);
    }
  }

 protected:
  bool any_occluded() const { return any_occluded_; }

 private:
  const LocalSampleSet& set_;
  int n_;
  bool any_occluded_ = false;
};

/// The sum of the local basis rows of a vertex's occluded rays: the inner loop of the shadowed pass (S
/// rows of bands^2 floats per vertex; in a closed room 3/4 of the rays are occluded, in no predictable
/// order, and the rays are cheap). Per batch it first lists the occluded rays (no branch per ray), then
/// adds their rows in ray order, the sums held in vector registers for up to 8 bands. Holds a copy of
/// the set's rows, each padded with zeros to width() floats. Read-only after construction: one may
/// serve every thread.
class OccludedRowSums {
 public:
  /// Copies set.basis (set.bands in 1..sh::kMaxBands).
  explicit OccludedRowSums(const LocalSampleSet& set);

  /// Floats of a sum buffer: bands^2 rounded up to a multiple of 8 (the padding stays 0).
  int width() const { return width_; }

  /// sum[0, width()) += the rows first .. first + batch.size() - 1 of the rays `batch` reports occluded
  /// (RayBatch::is_occluded, after Scene::occluded); returns how many were. The float additions are
  /// exactly those of adding each occluded ray's row in turn, in ray order, so the sums are
  /// bit-identical to that loop's. Precondition: first + batch.size() <= S.
  std::size_t add(const trace::RayBatch& batch, std::size_t first, float* sum) const;

 private:
  int width_ = 0;
  std::vector<float> rows_;  // S x width_, sample-major
};

/// Builds the set for (samples, seed): sh::hemisphere_directions_cosine, basis in float.
LocalSampleSet make_local_sample_set(int samples, int bands, std::uint32_t seed);

/// `sets` sets of `samples` cosine-distributed directions (interleaved sampling, Keller and Heidrich,
/// "Interleaved Sampling", EGWR 2001): set k is the points [k S, (k + 1) S) of the Sobol sequence
/// of make_local_sample_set (sh::hemisphere_directions_cosine(sets x S, seed)), so set 0 is
/// make_local_sample_set's and, for S a power of two, each set alone and every 2^m consecutive sets
/// aligned on 2^m together are (0,k,2)-nets of the unit square: points that trace different sets
/// sample complementary strata in both dimensions (elevation and azimuth). sets in 1..256, sets x S < 2^32.
LocalSampleSet make_interleaved_sample_sets(int samples, int bands, std::uint32_t seed, int sets);

/// S directions uniform on the hemisphere about +z (sh::hemisphere_directions_uniform) and the SH
/// basis of `bands` bands at each (the glossy passes, which weight by the BRDF rather than the cosine).
LocalSampleSet make_uniform_sample_set(int samples, int bands, std::uint32_t seed);
}  // namespace prt::bake
