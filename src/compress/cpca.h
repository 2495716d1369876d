#pragma once
// Clustered principal component analysis (CPCA; Sloan, Hall, Hart and Snyder, "Clustered Principal
// Components for Precomputed Radiance Transfer", SIGGRAPH 2003): P points of dimension D are split
// into K clusters, and each cluster k is fitted by its mean mu_k and N orthonormal principal directions
// b_k1..b_kN, so that point p of cluster k is approximated by
//   x_p ~ mu_k + sum_n w_pn b_kn,   w_pn = b_kn . (x_p - mu_k).
//
// Algorithm (iterative CPCA, the paper's section 4):
//   1. seeding: K distinct seed points by k-means++ (D^2 sampling) with a splitmix64 generator seeded by
//      `seed`; each cluster starts as its seed (mean = seed point, no directions);
//   2. assignment: every point goes to the cluster whose affine subspace reconstructs it best (least
//      squared residual |x - mu_k|^2 - sum_n (b_kn . (x - mu_k))^2, evaluated in double for the three
//      best candidates of a float pass and the point's current cluster);
//   3. empty clusters take the worst-reconstructed points (their own mean, error 0);
//   4. refit: per cluster, mean and top-N principal directions of its members (exact symmetric
//      eigensolver of the covariance for D <= 96, else subspace iteration with Rayleigh-Ritz warm-started
//      from the previous directions; the previous directions are kept if they capture more variance);
//   5. repeat 2-4 until the total squared residual falls by less than 1e-4 of itself, or `iterations`.
// Every step cannot increase the total squared residual, so error_history is non-increasing.
// FITTING ON A SUBSET (fit_points = S > 0 and P > S): steps 1-5 run on the S points floor(i P / S), i =
// 0..S-1 (evenly strided through the point order, so spread over the mesh or lightmap); then every
// point is assigned (2), empty clusters filled (3), every cluster refitted on all its members (4) and
// every point assigned again, its current cluster winning ties. The rounds then cost S / P of theirs;
// the model sees every point once in the last refit.
//
// Deterministic: work is split into fixed chunks of points or single clusters and every sum runs in a
// fixed order, so the result is byte-identical for any thread count.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace prt::compress {

struct CpcaOptions {
  int clusters = 0;        ///< K, 1..point count
  int pca = 0;             ///< N, 1..dimension: principal directions per cluster
  int iterations = 20;     ///< I >= 1: most assignment/refit rounds
  std::uint64_t seed = 1;  ///< seeds the k-means++ choice and the subspace-iteration start vectors
  int threads = 0;         ///< 0 = all cores; the result does not depend on it
  std::size_t fit_points = 0;  ///< S: > 0 and below the point count: the rounds fit this many points (above); 0: all
};

struct CpcaResult {
  std::size_t dimension = 0;            ///< D
  std::size_t count = 0;                ///< P
  int clusters = 0;                     ///< K
  int pca = 0;                          ///< N
  std::vector<float> means;             ///< K x D: mu_k at k * D
  std::vector<float> bases;             ///< K x N x D: b_kn at (k * N + n) * D, orthonormal per cluster
  std::vector<std::uint32_t> cluster;   ///< P: the cluster of each point
  std::vector<float> weights;           ///< P x N: w_pn at p * N + n
  std::vector<double> error_history;    ///< total squared residual after each round (double model) over the points the
                                        ///< rounds fit (the subset when fit_points applies), non-increasing
  double error = 0.0;                   ///< total squared residual of every point in the returned model
};

/// Throws prt::Error("<what>: ...") unless 1 <= K <= count, 1 <= N <= dimension and iterations >= 1
/// (and K <= fit_points when the subset applies).
void validate_cpca_options(std::size_t count, std::size_t dimension, const CpcaOptions& options, const std::string& what);

/// Runs CPCA on `count` points of `dimension` floats each, point-major (point p at p * dimension).
/// Validates with validate_cpca_options first. Values must be finite.
CpcaResult cpca(const float* points, std::size_t count, std::size_t dimension, const CpcaOptions& options,
                const std::string& what);

}  // namespace prt::compress
