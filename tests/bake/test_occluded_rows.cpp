// The shadowed pass's sum of occluded basis rows (bake/vertex_samples.h, OccludedRowSums) against the
// loop it replaces (add each occluded ray's row in turn: the bytes of every shadowed bake depend on
// its float sums) and against the same sums in double.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "bake/vertex_samples.h"
#include "trace/scene.h"

using namespace prt;

namespace {

// A batch of `count` rays whose occlusion answers are `occluded[first ..]`, set as Embree sets them
// (tfar = -infinity for an occluded ray, trace/scene.h).
void fill_batch(trace::RayBatch& batch, const std::vector<bool>& occluded, std::size_t first, std::size_t count) {
  batch.clear();
  for (std::size_t i = 0; i < count; ++i) {
    batch.push(glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, 1.0f));
    if (occluded[first + i]) batch.data()[i].ray.tfar = -trace::kInfinity;
  }
}

}  // namespace

TEST_CASE("OccludedRowSums adds the occluded rays' rows bit for bit as the per-ray loop, 1 to 10 bands", "[bake]") {
  // 300 samples: a full batch of 256 and one of 44. Masks: random (3/4 occluded, as in a closed room),
  // all occluded, none.
  constexpr std::size_t kSamples = 300, kBatch = 256;
  std::mt19937 rng(3);
  for (int bands = 1; bands <= 10; ++bands) {
    const bake::LocalSampleSet set = bake::make_local_sample_set(static_cast<int>(kSamples), bands, 7);
    const bake::OccludedRowSums sums(set);
    const int n = bands * bands;
    INFO(bands << " bands");
    CHECK(sums.width() % 8 == 0);
    CHECK(sums.width() >= n);
    CHECK(sums.width() < n + 8);
    for (int mask_kind = 0; mask_kind < 3; ++mask_kind) {
      std::vector<bool> occluded(kSamples);
      std::size_t expected_count = 0;
      for (std::size_t s = 0; s < kSamples; ++s) {
        occluded[s] = mask_kind == 0 ? rng() % 4 != 0 : mask_kind == 1;
        expected_count += occluded[s];
      }
      // The per-ray loop (float, sample order) and the double-precision sums.
      std::vector<float> expected(static_cast<std::size_t>(n), 0.0f);
      std::vector<double> exact(static_cast<std::size_t>(n), 0.0);
      for (std::size_t s = 0; s < kSamples; ++s) {
        if (!occluded[s]) continue;
        for (int c = 0; c < n; ++c) {
          expected[c] += set.basis[s * n + c];
          exact[c] += set.basis[s * n + c];
        }
      }
      std::vector<float> sum(static_cast<std::size_t>(sums.width()), 0.0f);
      trace::RayBatch batch(kBatch);
      std::size_t count = 0;
      for (std::size_t first = 0; first < kSamples; first += kBatch) {
        fill_batch(batch, occluded, first, std::min(kBatch, kSamples - first));
        count += sums.add(batch, first, sum.data());
      }
      INFO("mask " << mask_kind);
      CHECK(count == expected_count);
      CHECK(std::memcmp(sum.data(), expected.data(), sizeof(float) * n) == 0);
      for (int c = 0; c < n; ++c) {
        CHECK(std::abs(sum[c] - exact[c]) <= 1e-5 * kSamples);
        CHECK_FALSE(std::signbit(sum[c]) != std::signbit(expected[c]));  // +0, not -0, when nothing was added
      }
      for (int c = n; c < sums.width(); ++c) CHECK(sum[c] == 0.0f);  // the padding stays 0
    }
  }
}
