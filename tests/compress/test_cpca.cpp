// CPCA (src/compress/cpca.h) on synthetic point sets with known structure: exact recovery of points
// lying in K affine subspaces, a non-increasing error, thread-count independence, and bad K/N.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <map>
#include <random>
#include <set>

#include "compress/cpca.h"
#include "core/error.h"

using namespace prt;

namespace {

// Orthonormal rows (Gram-Schmidt in double) from Gaussian vectors.
std::vector<std::vector<double>> random_orthonormal(int count, int dimension, std::mt19937_64& rng) {
  std::normal_distribution<double> gauss;
  std::vector<std::vector<double>> rows;
  while (static_cast<int>(rows.size()) < count) {
    std::vector<double> v(static_cast<std::size_t>(dimension));
    for (double& x : v) x = gauss(rng);
    for (const auto& r : rows) {
      double d = 0;
      for (int i = 0; i < dimension; ++i) d += v[i] * r[i];
      for (int i = 0; i < dimension; ++i) v[i] -= d * r[i];
    }
    double n = 0;
    for (double x : v) n += x * x;
    for (double& x : v) x /= std::sqrt(n);
    rows.push_back(v);
  }
  return rows;
}

// `clusters` affine subspaces of dimension `n` (means ~ 10 apart, coefficients in [-1, 1]), `per`
// points each, shuffled; `truth` gets the subspace of each point.
std::vector<float> subspace_points(int clusters, int n, int dimension, int per, std::vector<int>& truth, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<std::pair<int, std::vector<double>>> points;
  for (int k = 0; k < clusters; ++k) {
    std::vector<double> mean(static_cast<std::size_t>(dimension));
    for (double& m : mean) m = 10.0 * unit(rng);
    const auto basis = random_orthonormal(n, dimension, rng);
    for (int p = 0; p < per; ++p) {
      std::vector<double> x = mean;
      for (int j = 0; j < n; ++j) {
        const double w = unit(rng);
        for (int i = 0; i < dimension; ++i) x[i] += w * basis[j][i];
      }
      points.push_back({k, x});
    }
  }
  std::shuffle(points.begin(), points.end(), rng);
  std::vector<float> flat;
  truth.clear();
  for (const auto& [k, x] : points) {
    truth.push_back(k);
    for (double v : x) flat.push_back(static_cast<float>(v));
  }
  return flat;
}

// Largest |x - (mu_k + sum_n w_n b_n)| over all values, recomputed here from the result's arrays.
double max_reconstruction_error(const std::vector<float>& x, const compress::CpcaResult& r) {
  double worst = 0;
  const std::size_t D = r.dimension, N = static_cast<std::size_t>(r.pca);
  for (std::size_t p = 0; p < r.count; ++p) {
    const std::size_t k = r.cluster[p];
    for (std::size_t i = 0; i < D; ++i) {
      double v = r.means[k * D + i];
      for (std::size_t j = 0; j < N; ++j) v += static_cast<double>(r.weights[p * N + j]) * r.bases[(k * N + j) * D + i];
      worst = std::max(worst, std::abs(v - x[p * D + i]));
    }
  }
  return worst;
}

compress::CpcaOptions options(int clusters, int pca, int threads = 1) {
  compress::CpcaOptions o;
  o.clusters = clusters;
  o.pca = pca;
  o.threads = threads;
  return o;
}

}  // namespace

TEST_CASE("cpca recovers points lying exactly in K affine subspaces of dimension N (1e-6)", "[compress]") {
  // D = 40 takes the covariance eigensolver, D = 300 the subspace iteration.
  for (int dimension : {40, 300}) {
    std::vector<int> truth;
    const std::vector<float> x = subspace_points(6, 4, dimension, 150, truth, 7 + dimension);
    const compress::CpcaResult r = compress::cpca(x.data(), truth.size(), static_cast<std::size_t>(dimension), options(6, 4), "synthetic");
    INFO("dimension " << dimension << ", rounds " << r.error_history.size());
    // The partition is the true one (a bijection between found and true clusters).
    std::map<std::uint32_t, std::set<int>> found;
    for (std::size_t p = 0; p < truth.size(); ++p) found[r.cluster[p]].insert(truth[p]);
    CHECK(found.size() == 6);
    for (const auto& [k, members] : found) CHECK(members.size() == 1);
    CHECK(max_reconstruction_error(x, r) <= 1e-6 * 10.0 * 2.0);  // values are up to ~12 in magnitude
    // Each cluster's directions are orthonormal.
    for (int k = 0; k < 6; ++k)
      for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b) {
          double d = 0;
          for (int i = 0; i < dimension; ++i)
            d += static_cast<double>(r.bases[(k * 4 + a) * dimension + i]) * r.bases[(k * 4 + b) * dimension + i];
          CHECK(std::abs(d - (a == b ? 1.0 : 0.0)) < 1e-5);
        }
  }
}

TEST_CASE("cpca: the error does not increase between iterations and matches the returned model", "[compress]") {
  // Points without exact structure: smooth random functions plus noise, so rounds keep changing.
  std::mt19937_64 rng(3);
  std::normal_distribution<double> gauss;
  const int D = 120, P = 3000;
  std::vector<float> x(static_cast<std::size_t>(P) * D);
  for (int p = 0; p < P; ++p) {
    const double a = gauss(rng), b = gauss(rng), c = gauss(rng);
    for (int i = 0; i < D; ++i)
      x[static_cast<std::size_t>(p) * D + i] = static_cast<float>(std::sin(a * i * 0.05 + b) * c + 0.1 * gauss(rng));
  }
  compress::CpcaOptions o = options(12, 3, 2);
  o.iterations = 30;
  const compress::CpcaResult r = compress::cpca(x.data(), P, D, o, "smooth");
  REQUIRE(r.error_history.size() >= 3);
  for (std::size_t i = 1; i < r.error_history.size(); ++i) {
    INFO("round " << i);
    CHECK(r.error_history[i] <= r.error_history[i - 1]);
  }
  CHECK(r.error_history.back() < 0.9 * r.error_history.front());
  // The last error is the squared residual of the returned (float) model, recomputed here.
  double sum = 0;
  const std::size_t N = 3;
  for (std::size_t p = 0; p < static_cast<std::size_t>(P); ++p) {
    const std::size_t k = r.cluster[p];
    for (std::size_t i = 0; i < static_cast<std::size_t>(D); ++i) {
      double v = r.means[k * D + i];
      for (std::size_t j = 0; j < N; ++j) v += static_cast<double>(r.weights[p * N + j]) * r.bases[(k * N + j) * D + i];
      sum += (v - x[p * D + i]) * (v - x[p * D + i]);
    }
  }
  CHECK(sum == Approx(r.error_history.back()).epsilon(1e-3));
}

TEST_CASE("cpca output is byte-identical for 1 and 2 threads", "[compress]") {
  std::vector<int> truth;
  std::vector<float> x = subspace_points(5, 3, 150, 120, truth, 11);
  std::mt19937_64 rng(5);
  std::normal_distribution<double> gauss;
  for (float& v : x) v += static_cast<float>(0.05 * gauss(rng));  // not exact: many rounds
  compress::CpcaOptions o = options(9, 3, 1);
  const compress::CpcaResult one = compress::cpca(x.data(), truth.size(), 150, o, "noisy");
  o.threads = 2;
  const compress::CpcaResult two = compress::cpca(x.data(), truth.size(), 150, o, "noisy");
  CHECK(one.error_history.size() > 1);
  CHECK(one.cluster == two.cluster);
  CHECK(std::memcmp(one.means.data(), two.means.data(), one.means.size() * 4) == 0);
  CHECK(std::memcmp(one.bases.data(), two.bases.data(), one.bases.size() * 4) == 0);
  CHECK(std::memcmp(one.weights.data(), two.weights.data(), one.weights.size() * 4) == 0);
  CHECK(one.error_history == two.error_history);
}

TEST_CASE("cpca fitted on a subset: exact recovery from 3 points per cluster, every point assigned, any thread count", "[compress]") {
  // 6 subspaces of dimension 4, 150 points each; the rounds see 18 points (3 per cluster on average:
  // too few for 4 directions), so only the last refit on every member can recover the subspaces.
  std::vector<int> truth;
  const std::vector<float> x = subspace_points(6, 4, 40, 150, truth, 21);
  compress::CpcaOptions o = options(6, 4, 1);
  o.fit_points = 18;
  const compress::CpcaResult one = compress::cpca(x.data(), truth.size(), 40, o, "subset");
  std::map<std::uint32_t, std::set<int>> found;
  for (std::size_t p = 0; p < truth.size(); ++p) found[one.cluster[p]].insert(truth[p]);
  CHECK(found.size() == 6);
  for (const auto& [k, members] : found) CHECK(members.size() == 1);
  CHECK(max_reconstruction_error(x, one) <= 1e-6 * 10.0 * 2.0);
  CHECK(one.error <= 1e-8);
  o.threads = 2;
  const compress::CpcaResult two = compress::cpca(x.data(), truth.size(), 40, o, "subset");
  CHECK(one.cluster == two.cluster);
  CHECK(std::memcmp(one.bases.data(), two.bases.data(), one.bases.size() * 4) == 0);
  CHECK(std::memcmp(one.weights.data(), two.weights.data(), one.weights.size() * 4) == 0);
  // More clusters than the subset holds is refused.
  o.clusters = 19;
  CHECK_THROWS_WITH(compress::cpca(x.data(), truth.size(), 40, o, "subset"), Catch::Contains("subset: clusters 19 must not exceed the points fitted (18)"));
}

TEST_CASE("cpca: bad K, N or iterations are one-line errors naming the input", "[compress]") {
  const std::vector<float> x(10 * 4, 1.0f);
  const auto message = [&](int k, int n, int iterations) {
    compress::CpcaOptions o = options(k, n);
    o.iterations = iterations;
    try {
      compress::cpca(x.data(), 10, 4, o, "in.prt");
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK(message(0, 2, 5) == "in.prt: clusters 0 must be between 1 and the number of points (10)");
  CHECK(message(11, 2, 5) == "in.prt: clusters 11 must be between 1 and the number of points (10)");
  CHECK(message(2, 0, 5) == "in.prt: pca 0 must be between 1 and the dimension of the transfer (4 values per point)");
  CHECK(message(2, 5, 5) == "in.prt: pca 5 must be between 1 and the dimension of the transfer (4 values per point)");
  CHECK(message(2, 2, 0) == "in.prt: iterations 0 must be at least 1");
  // K = P of identical points (every cluster seeded, none empty, error 0) is fine.
  CHECK(message(10, 4, 5) == "no error");
}
