#include <catch2/catch.hpp>

#include <atomic>
#include <stdexcept>
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
