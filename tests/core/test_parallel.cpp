#include <catch2/catch.hpp>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

#include "core/parallel.h"

TEST_CASE("parallel_for visits every item exactly once for any thread count", "[core]") {
  for (int threads : {1, 2, 3, 8}) {
    for (std::size_t grain : {1u, 7u, 64u, 1000u}) {
      std::vector<std::atomic<int>> visits(997);
      prt::parallel_for(visits.size(), grain, threads, [&](std::size_t b, std::size_t e) {
        for (std::size_t i = b; i < e; ++i) visits[i].fetch_add(1);
      });
      for (auto& v : visits) REQUIRE(v.load() == 1);
    }
  }
}

TEST_CASE("parallel_for rethrows the body's exception", "[core]") {
  CHECK_THROWS_AS(prt::parallel_for(100, 1, 2,
                                    [](std::size_t b, std::size_t) {
                                      if (b == 50) throw std::runtime_error("boom");
                                    }),
                  std::runtime_error);
}

TEST_CASE("parallel_for with zero items calls nothing", "[core]") {
  bool called = false;
  prt::parallel_for(0, 1, 2, [&](std::size_t, std::size_t) { called = true; });
  CHECK_FALSE(called);
}

namespace {
std::atomic<int> g_threads_seen{0};
struct ThreadMarker {
  ThreadMarker() { g_threads_seen.fetch_add(1); }
  void touch() {}
};
thread_local ThreadMarker t_marker;
}  // namespace

TEST_CASE("parallel_for keeps its threads between calls", "[core]") {
  // A thread_local's constructor runs once per thread that uses it, so this counts the distinct
  // threads (not thread ids, which the OS reuses) that ran a chunk over 40 calls of 3 threads each.
  prt::parallel_for(64, 1, 3, [](std::size_t, std::size_t) { t_marker.touch(); });  // the pool's first use
  const int before = g_threads_seen.load();
  for (int call = 0; call < 40; ++call)
    prt::parallel_for(64, 1, 3, [](std::size_t, std::size_t) {
      t_marker.touch();
      std::this_thread::sleep_for(std::chrono::microseconds(50));
    });
  CHECK(g_threads_seen.load() - before <= 2);  // at most the pool threads not yet used before; no new ones per call
}

TEST_CASE("parallel_for from inside a body and from two threads at once visits every item once", "[core]") {
  std::vector<std::atomic<int>> visits(64 * 50);
  prt::parallel_for(64, 4, 3, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i)
      prt::parallel_for(50, 7, 3, [&](std::size_t b2, std::size_t e2) {
        for (std::size_t j = b2; j < e2; ++j) visits[i * 50 + j].fetch_add(1);
      });
  });
  for (auto& v : visits) REQUIRE(v.load() == 1);

  std::vector<std::atomic<int>> a(5000), b(5000);
  auto fill = [](std::vector<std::atomic<int>>& out) {
    for (int round = 0; round < 20; ++round)
      prt::parallel_for(out.size(), 13, 4, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) out[i].fetch_add(1);
      });
  };
  std::thread other([&] { fill(a); });
  fill(b);
  other.join();
  for (std::size_t i = 0; i < a.size(); ++i) REQUIRE((a[i].load() == 20 && b[i].load() == 20));
}
