#pragma once
// The hemisphere sample set every vertex traces and per-vertex frames: internal to prt_bake.
#include <cstdint>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "trace/scene.h"

namespace prt::bake {

/// S hemisphere directions about +z (local frame) and the SH basis at each of them.
struct LocalSampleSet {
  int bands = 0;
  std::vector<glm::vec3> directions;  ///< S unit vectors, z >= 0
  std::vector<float> basis;           ///< S x bands^2, sample-major: basis[s * bands^2 + i] = Y_i(directions[s])
};

/// The part every visibility worker of trace::trace_vertex_rays shares: per vertex, hands the basis row
/// of each occluded sample to Derived::add_occluded(const float* y) (after Derived::clear() at the start)
/// and remembers whether any ray was occluded. Derived adds finish(v, frame).
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

/// Builds the set for (samples, seed): sh::hemisphere_directions_cosine, basis in float.
LocalSampleSet make_local_sample_set(int samples, int bands, std::uint32_t seed);

/// S directions uniform on the hemisphere about +z (sh::hemisphere_directions_uniform) and the SH
/// basis of `bands` bands at each (the glossy passes, which weight by the BRDF rather than the cosine).
LocalSampleSet make_uniform_sample_set(int samples, int bands, std::uint32_t seed);
}  // namespace prt::bake
