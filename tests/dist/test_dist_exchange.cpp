// src/dist on real ranks (ctest runs this under mpirun -np 3): the partition tiles the items, the
// exchanges deliver every item's row bit for bit to where it belongs, and the input check throws the
// same error on every rank. The truth is computed here independently: each row's content is a closed
// function of its item index, and the expected split is floor(N r / P).
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include <cstdint>
#include <cstring>
#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

#include "dist/context.h"
#include "dist/exchange.h"
#include "dist/inputs.h"
#include "dist/partition.h"

using namespace prt;

namespace {

const dist::Context& world() { return dist::Context::world(); }

// The value k of item i's row: distinct for every (i, k), and not a float that survives a conversion
// by accident (negative zero and NaN payloads included to check that bytes, not values, travel).
float row_value(std::size_t i, std::size_t k) {
  if (k == 0 && i % 7 == 3) return -0.0f;
  if (k == 1 && i % 11 == 5) {
    const std::uint32_t bits = 0x7fc00000u | static_cast<std::uint32_t>(i & 0xffff);
    float f;
    std::memcpy(&f, &bits, sizeof f);
    return f;
  }
  return static_cast<float>(i) * 1.25f + static_cast<float>(k) / 8.0f;
}

bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// A fixed pseudo-random permutation (the role of the Morton order).
std::vector<std::uint32_t> permutation(std::size_t n) {
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  std::mt19937 rng(12345);
  std::shuffle(order.begin(), order.end(), rng);
  return order;
}

// Fills this rank's items (positions of its range in `order`) with row_value, the rest with a sentinel.
std::vector<float> my_rows(std::size_t n, std::size_t per_item, const std::vector<std::uint32_t>& order) {
  std::vector<float> values(n * per_item, 999.0f);
  const dist::Range mine = dist::my_range(world(), n);
  for (std::size_t k = mine.begin; k < mine.end; ++k)
    for (std::size_t c = 0; c < per_item; ++c) values[order[k] * per_item + c] = row_value(order[k], c);
  return values;
}

}  // namespace

TEST_CASE("the job has the ranks mpirun started", "[dist]") {
  CHECK(world().uses_mpi());
  CHECK(world().size() == 3);
  CHECK(world().sum(static_cast<std::uint64_t>(world().rank() + 1)) == 6u);  // 1 + 2 + 3
}

TEST_CASE("partition: contiguous runs of floor(N r / P) that tile the items", "[dist]") {
  for (std::size_t n : {0u, 1u, 2u, 5u, 64u, 1000u, 437123u})
    for (int p = 1; p <= 7; ++p) {
      const std::vector<dist::Range> runs = dist::partitions(n, p);
      REQUIRE(runs.size() == static_cast<std::size_t>(p));
      std::size_t expected_begin = 0;
      for (int r = 0; r < p; ++r) {
        CHECK(runs[r].begin == expected_begin);
        CHECK(runs[r].end == n * static_cast<std::size_t>(r + 1) / static_cast<std::size_t>(p));
        CHECK(runs[r].size() + 1 >= n / p);  // sizes differ by at most one
        CHECK(runs[r].size() <= n / p + 1);
        expected_begin = runs[r].end;
      }
      CHECK(expected_begin == n);
    }
  CHECK_THROWS(dist::partition(10, 3, 3));
}

TEST_CASE("allgather_items gives every rank every row, bit for bit", "[dist]") {
  for (std::size_t n : {1u, 2u, 3u, 10u, 1237u}) {
    const std::size_t per_item = 5;
    const std::vector<std::uint32_t> order = permutation(n);
    std::vector<float> values = my_rows(n, per_item, order);
    dist::allgather_items(world(), values, per_item, &order);
    std::size_t wrong = 0;
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t c = 0; c < per_item; ++c) wrong += same_bits(values[i * per_item + c], row_value(i, c)) ? 0 : 1;
    INFO("n = " << n << ", rank " << world().rank());
    CHECK(wrong == 0);
  }
}

TEST_CASE("gather_items gives rank 0 every row and leaves the others' alone", "[dist]") {
  const std::size_t n = 1001, per_item = 3;
  std::vector<std::uint32_t> identity(n);
  std::iota(identity.begin(), identity.end(), 0u);
  std::vector<float> values = my_rows(n, per_item, identity);
  const std::vector<float> before = values;
  const dist::ExchangeStats stats_before = world().stats();
  dist::gather_items(world(), values, per_item);  // nullptr order: items in index order
  if (world().is_root()) {
    std::size_t wrong = 0;
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t c = 0; c < per_item; ++c) wrong += same_bits(values[i * per_item + c], row_value(i, c)) ? 0 : 1;
    CHECK(wrong == 0);
    const dist::Range mine = dist::my_range(world(), n);
    CHECK(world().stats().bytes_received - stats_before.bytes_received == (n - mine.size()) * per_item * sizeof(float));
  } else {
    CHECK(std::memcmp(values.data(), before.data(), values.size() * sizeof(float)) == 0);
  }
}

TEST_CASE("check_same_inputs: equal inputs pass, a difference on one rank throws on every rank", "[dist]") {
  const std::vector<dist::Fingerprint> same = {{"a.obj", 7}, {"the options", 9}};
  CHECK_NOTHROW(dist::check_same_inputs(world(), same));
  // Rank 2 read another mesh.
  const std::vector<dist::Fingerprint> differs = {{"a.obj", world().rank() == 2 ? 8u : 7u}, {"the options", 9}};
  try {
    dist::check_same_inputs(world(), differs);
    FAIL("no error on rank " << world().rank());
  } catch (const dist::CollectiveError& e) {
    CHECK(std::string(e.what()) ==
          "a.obj: differs between ranks (rank 0: 0x0000000000000007, rank 2: 0x0000000000000008); every rank must read "
          "the same inputs with the same options");
  }
  // Rank 1 runs another command (another number of inputs).
  std::vector<dist::Fingerprint> count = same;
  if (world().rank() == 1) count.push_back({"extra", 1});
  CHECK_THROWS_AS(dist::check_same_inputs(world(), count), dist::CollectiveError);
}

int main(int argc, char** argv) {
  const int failed = Catch::Session().run(argc, argv);
  // Every rank must agree before MPI ends, else a failing rank's exit would look like a crash.
  const std::uint64_t failures = dist::Context::world().sum(failed != 0 ? 1u : 0u);
  dist::Context::world().finalize();
  return failures == 0 ? 0 : 1;
}
