#include "compress/cpca.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include <Eigen/Dense>

#include "core/error.h"
#include "core/parallel.h"

namespace prt::compress {

namespace {

using RowMatrixF = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using MatrixD = Eigen::MatrixXd;

constexpr std::size_t kPointGrain = 256;   // points per parallel chunk (fixed: results do not depend on threads)
constexpr std::size_t kDirectLimit = 96;   // D up to this: exact eigensolver of the D x D covariance
constexpr int kCandidates = 3;             // float-pass candidates re-evaluated in double
constexpr int kOversampling = 4;           // extra subspace-iteration vectors
constexpr int kFirstSubspaceIterations = 10, kWarmSubspaceIterations = 3;
constexpr double kStopFraction = 1e-4;

std::uint64_t splitmix64(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}
double uniform01(std::uint64_t& state) { return static_cast<double>(splitmix64(state) >> 11) * 0x1.0p-53; }

// The current fit, in double. Directions of a cluster may be zero (a seed has none yet).
struct Model {
  std::size_t dimension = 0;
  int clusters = 0, pca = 0;
  std::vector<double> mean;   // K x D
  std::vector<double> basis;  // K x N x D
  const double* mean_of(int k) const { return &mean[static_cast<std::size_t>(k) * dimension]; }
  const double* direction(int k, int n) const { return &basis[(static_cast<std::size_t>(k) * pca + n) * dimension]; }
};

// sum_i a[i] b[i] in double over eight interleaved lanes added in a fixed order: vectorisable without
// reassociation, and the same result wherever the arrays lie in memory.
template <typename A, typename B>
double dot(const A* a, const B* b, std::size_t n) {
  double lane[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  std::size_t i = 0;
  for (; i + 8 <= n; i += 8)
    for (std::size_t j = 0; j < 8; ++j) lane[j] += static_cast<double>(a[i + j]) * static_cast<double>(b[i + j]);
  for (; i < n; ++i) lane[i % 8] += static_cast<double>(a[i]) * static_cast<double>(b[i]);
  return ((lane[0] + lane[4]) + (lane[1] + lane[5])) + ((lane[2] + lane[6]) + (lane[3] + lane[7]));
}

// Squared residual of x in cluster k (|d|^2 - sum_n (b_n . d)^2, d = x - mu_k, orthonormal or zero b_n);
// writes the weights if `weights` is given. `scratch` holds D doubles.
double residual2(const Model& m, int k, const float* x, double* weights, std::vector<double>& scratch) {
  const std::size_t D = m.dimension;
  const double* mu = m.mean_of(k);
  scratch.resize(D);
  double* d = scratch.data();
  for (std::size_t i = 0; i < D; ++i) d[i] = static_cast<double>(x[i]) - mu[i];
  double captured = 0.0;
  for (int n = 0; n < m.pca; ++n) {
    const double w = dot(m.direction(k, n), d, D);
    captured += w * w;
    if (weights) weights[n] = w;
  }
  return std::max(0.0, dot(d, d, D) - captured);
}

double distance2(const float* a, const float* b, std::size_t D, std::vector<double>& scratch) {
  scratch.resize(D);
  for (std::size_t i = 0; i < D; ++i) scratch[i] = static_cast<double>(a[i]) - static_cast<double>(b[i]);
  return dot(scratch.data(), scratch.data(), D);
}

// k-means++ seeds: the first uniformly, each next with probability proportional to the squared
// distance to the nearest seed so far (a point equal to a seed is never picked while others are left).
Model seed_model(const float* x, std::size_t P, std::size_t D, const CpcaOptions& o) {
  Model m;
  m.dimension = D;
  m.clusters = o.clusters;
  m.pca = o.pca;
  m.mean.assign(static_cast<std::size_t>(o.clusters) * D, 0.0);
  m.basis.assign(static_cast<std::size_t>(o.clusters) * o.pca * D, 0.0);
  std::uint64_t rng = o.seed;
  std::vector<double> nearest(P, std::numeric_limits<double>::infinity());
  std::vector<char> chosen(P, 0);
  std::size_t pick = static_cast<std::size_t>(splitmix64(rng) % P);
  for (int k = 0; k < o.clusters; ++k) {
    chosen[pick] = 1;
    const float* c = x + pick * D;
    std::copy(c, c + D, m.mean.begin() + static_cast<std::ptrdiff_t>(k * D));
    if (k + 1 == o.clusters) break;
    parallel_for(P, kPointGrain, o.threads, [&](std::size_t begin, std::size_t end) {
      std::vector<double> scratch;
      for (std::size_t p = begin; p < end; ++p) nearest[p] = std::min(nearest[p], distance2(x + p * D, c, D, scratch));
    });
    double total = 0.0;
    for (std::size_t p = 0; p < P; ++p) total += chosen[p] ? 0.0 : nearest[p];
    std::size_t next = P;
    if (total > 0.0) {
      double target = uniform01(rng) * total, running = 0.0;
      for (std::size_t p = 0; p < P && next == P; ++p) {
        if (chosen[p] || nearest[p] <= 0.0) continue;
        running += nearest[p];
        if (running > target) next = p;
      }
      for (std::size_t p = P; p-- > 0 && next == P;)  // rounding at the end of the walk
        if (!chosen[p] && nearest[p] > 0.0) next = p;
    }
    for (std::size_t p = 0; p < P && next == P; ++p)  // only duplicates of seeds are left
      if (!chosen[p]) next = p;
    pick = next;
  }
  return m;
}

// Rows [mu_k, b_k1, ..., b_kN] of every cluster, as float, for the candidate pass.
RowMatrixF stacked_rows(const Model& m) {
  const int stride = m.pca + 1;
  RowMatrixF rows(static_cast<Eigen::Index>(m.clusters) * stride, static_cast<Eigen::Index>(m.dimension));
  for (int k = 0; k < m.clusters; ++k) {
    for (std::size_t i = 0; i < m.dimension; ++i) rows(k * stride, static_cast<Eigen::Index>(i)) = static_cast<float>(m.mean_of(k)[i]);
    for (int n = 0; n < m.pca; ++n)
      for (std::size_t i = 0; i < m.dimension; ++i)
        rows(k * stride + 1 + n, static_cast<Eigen::Index>(i)) = static_cast<float>(m.direction(k, n)[i]);
  }
  return rows;
}

// Step 2: each point's best cluster (see the header); `error` gets its exact squared residual there.
// `current` (empty on the first round) is always one of the candidates.
void assign(const float* x, std::size_t P, const Model& m, int threads, std::vector<std::uint32_t>& cluster,
            std::vector<double>& error) {
  const std::size_t D = m.dimension;
  const int K = m.clusters, stride = m.pca + 1;
  const RowMatrixF rows = stacked_rows(m);
  std::vector<double> mean_norm2(static_cast<std::size_t>(K)), mean_projection(static_cast<std::size_t>(K) * m.pca);
  for (int k = 0; k < K; ++k) {
    mean_norm2[static_cast<std::size_t>(k)] = dot(m.mean_of(k), m.mean_of(k), D);
    for (int n = 0; n < m.pca; ++n) mean_projection[static_cast<std::size_t>(k) * m.pca + n] = dot(m.direction(k, n), m.mean_of(k), D);
  }
  const bool has_current = !cluster.empty();
  if (!has_current) cluster.assign(P, 0);
  error.assign(P, 0.0);
  parallel_for(P, kPointGrain, threads, [&](std::size_t begin, std::size_t end) {
    const Eigen::Map<const RowMatrixF> block(x + begin * D, static_cast<Eigen::Index>(end - begin), static_cast<Eigen::Index>(D));
    const RowMatrixF products = block * rows.transpose();  // (points) x K(N+1)
    std::vector<std::pair<double, int>> estimate(static_cast<std::size_t>(K));
    std::vector<double> scratch;
    for (std::size_t p = begin; p < end; ++p) {
      const float* xp = x + p * D;
      const double xx = dot(xp, xp, D);
      const auto row = static_cast<Eigen::Index>(p - begin);
      for (int k = 0; k < K; ++k) {
        double e = xx - 2.0 * products(row, k * stride) + mean_norm2[static_cast<std::size_t>(k)];
        for (int n = 0; n < m.pca; ++n) {
          const double w = products(row, k * stride + 1 + n) - mean_projection[static_cast<std::size_t>(k) * m.pca + n];
          e -= w * w;
        }
        estimate[static_cast<std::size_t>(k)] = {e, k};
      }
      const int c = std::min(kCandidates, K);
      std::partial_sort(estimate.begin(), estimate.begin() + c, estimate.end());
      int best = has_current ? static_cast<int>(cluster[p]) : estimate[0].second;
      double best_error = residual2(m, best, xp, nullptr, scratch);
      for (int i = 0; i < c; ++i) {
        const int k = estimate[static_cast<std::size_t>(i)].second;
        if (has_current && k == static_cast<int>(cluster[p])) continue;
        const double e = residual2(m, k, xp, nullptr, scratch);
        if (e < best_error || (e == best_error && k < best)) best = k, best_error = e;
      }
      cluster[p] = static_cast<std::uint32_t>(best);
      error[p] = best_error;
    }
  });
}

// Step 3: every empty cluster (in index order) takes the worst-reconstructed point of a cluster that
// has more than one (ties: lowest index) and becomes that point, with no directions.
void fill_empty_clusters(const float* x, std::size_t P, Model& m, std::vector<std::uint32_t>& cluster, std::vector<double>& error) {
  std::vector<std::size_t> size(static_cast<std::size_t>(m.clusters), 0);
  for (std::uint32_t c : cluster) ++size[c];
  std::vector<std::size_t> order(P);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return error[a] > error[b]; });
  std::size_t next = 0;
  for (int k = 0; k < m.clusters; ++k) {
    if (size[static_cast<std::size_t>(k)] > 0) continue;
    while (next < P && size[cluster[order[next]]] < 2) ++next;
    if (next == P) break;  // cannot happen while K <= P
    const std::size_t p = order[next++];
    --size[cluster[p]];
    cluster[p] = static_cast<std::uint32_t>(k);
    size[static_cast<std::size_t>(k)] = 1;
    error[p] = 0.0;
    std::copy(x + p * m.dimension, x + (p + 1) * m.dimension, m.mean.begin() + static_cast<std::ptrdiff_t>(k * m.dimension));
    std::fill_n(m.basis.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(k) * m.pca * m.dimension),
                static_cast<std::size_t>(m.pca) * m.dimension, 0.0);
  }
}

// Top-N principal directions (columns, orthonormal) of the centred members Y (n x D).
MatrixD principal_directions(const MatrixD& Y, int N, const MatrixD& previous, std::uint64_t seed) {
  const Eigen::Index D = Y.cols();
  if (static_cast<std::size_t>(D) <= kDirectLimit) {
    const MatrixD covariance = Y.transpose() * Y;
    const Eigen::SelfAdjointEigenSolver<MatrixD> eig(covariance);
    return eig.eigenvectors().rightCols(N).rowwise().reverse();
  }
  const Eigen::Index b = std::min<Eigen::Index>(D, N + kOversampling);
  MatrixD Q(D, b);
  std::uint64_t rng = seed;
  for (Eigen::Index j = 0; j < b; ++j)
    for (Eigen::Index i = 0; i < D; ++i) Q(i, j) = 2.0 * uniform01(rng) - 1.0;
  const bool warm = previous.cols() == N && previous.norm() > 0.0;
  if (warm) Q.leftCols(N) = previous;
  const int iterations = warm ? kWarmSubspaceIterations : kFirstSubspaceIterations;
  for (int t = 0; t < iterations; ++t) {
    const MatrixD Z = Y * Q;
    const MatrixD grown = Y.transpose() * Z;
    Q = grown.householderQr().householderQ() * MatrixD::Identity(D, b);
  }
  const MatrixD Z = Y * Q;
  const Eigen::SelfAdjointEigenSolver<MatrixD> eig(Z.transpose() * Z);
  return Q * eig.eigenvectors().rightCols(N).rowwise().reverse();
}

// Step 4 for cluster k: mean and directions of its members; keeps the previous directions if they
// capture more of the members' variance (so the step cannot increase the error).
void refit_cluster(const float* x, const std::vector<std::size_t>& members, int k, std::uint64_t seed, Model& m) {
  const std::size_t D = m.dimension, n = members.size();
  double* mean = &m.mean[static_cast<std::size_t>(k) * D];
  std::fill_n(mean, D, 0.0);
  for (std::size_t p : members)
    for (std::size_t i = 0; i < D; ++i) mean[i] += x[p * D + i];
  for (std::size_t i = 0; i < D; ++i) mean[i] /= static_cast<double>(n);
  MatrixD Y(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(D));
  for (std::size_t r = 0; r < n; ++r)
    for (std::size_t i = 0; i < D; ++i) Y(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(i)) = x[members[r] * D + i] - mean[i];
  double* basis = &m.basis[static_cast<std::size_t>(k) * m.pca * D];
  MatrixD previous(static_cast<Eigen::Index>(D), m.pca);
  for (int j = 0; j < m.pca; ++j)
    for (std::size_t i = 0; i < D; ++i) previous(static_cast<Eigen::Index>(i), j) = basis[j * D + i];
  const MatrixD fresh = principal_directions(Y, m.pca, previous, seed);
  const MatrixD& keep = (Y * fresh).squaredNorm() >= (Y * previous).squaredNorm() ? fresh : previous;
  for (int j = 0; j < m.pca; ++j)
    for (std::size_t i = 0; i < D; ++i) basis[j * D + i] = keep(static_cast<Eigen::Index>(i), j);
}

void refit(const float* x, const std::vector<std::uint32_t>& cluster, std::uint64_t seed, int round, int threads, Model& m) {
  std::vector<std::vector<std::size_t>> members(static_cast<std::size_t>(m.clusters));
  for (std::size_t p = 0; p < cluster.size(); ++p) members[cluster[p]].push_back(p);
  parallel_for(static_cast<std::size_t>(m.clusters), 1, threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) {
      std::uint64_t state = seed ^ (0xA24BAED4963EE407ull * (k + 1)) ^ (0x9FB21C651E98DF25ull * static_cast<std::uint64_t>(round + 1));
      refit_cluster(x, members[k], static_cast<int>(k), splitmix64(state), m);
    }
  });
}

// Total squared residual of every point in its cluster; fills the weights if given. Chunk sums are added
// in chunk order.
double total_error(const float* x, std::size_t P, const Model& m, const std::vector<std::uint32_t>& cluster, int threads,
                   std::vector<double>* weights) {
  const std::size_t chunks = (P + kPointGrain - 1) / kPointGrain;
  std::vector<double> partial(chunks, 0.0);
  parallel_for(P, kPointGrain, threads, [&](std::size_t begin, std::size_t end) {
    double s = 0.0;
    std::vector<double> scratch;
    for (std::size_t p = begin; p < end; ++p)
      s += residual2(m, static_cast<int>(cluster[p]), x + p * m.dimension,
                     weights ? weights->data() + p * static_cast<std::size_t>(m.pca) : nullptr, scratch);
    partial[begin / kPointGrain] = s;
  });
  return std::accumulate(partial.begin(), partial.end(), 0.0);
}

}  // namespace

void validate_cpca_options(std::size_t count, std::size_t dimension, const CpcaOptions& o, const std::string& what) {
  if (count == 0) fail_file(what, "no points to compress");
  if (o.clusters < 1 || static_cast<std::size_t>(o.clusters) > count)
    fail_file_option(what, "clusters", " " + std::to_string(o.clusters) + " must be between 1 and the number of points (" +
                                           std::to_string(count) + ")");
  if (o.pca < 1 || static_cast<std::size_t>(o.pca) > dimension)
    fail_file_option(what, "pca", " " + std::to_string(o.pca) + " must be between 1 and the dimension of the transfer (" +
                                      std::to_string(dimension) + " values per point)");
  if (o.iterations < 1) fail_file_option(what, "iterations", " " + std::to_string(o.iterations) + " must be at least 1");
  if (o.fit_points > 0 && o.fit_points < count && static_cast<std::size_t>(o.clusters) > o.fit_points)
    fail_file_option(what, "clusters", " " + std::to_string(o.clusters) + " must not exceed the points fitted (" +
                                           std::to_string(o.fit_points) + ")");
}

namespace {

// Steps 1-5 on P points: the rounds; returns the clusters of the points.
std::vector<std::uint32_t> fit_rounds(const float* x, std::size_t P, const CpcaOptions& o, Model& m, std::vector<double>& history) {
  std::vector<std::uint32_t> cluster;
  std::vector<double> error;
  for (int round = 0; round < o.iterations; ++round) {
    assign(x, P, m, o.threads, cluster, error);
    fill_empty_clusters(x, P, m, cluster, error);
    refit(x, cluster, o.seed, round, o.threads, m);
    const double e = total_error(x, P, m, cluster, o.threads, nullptr);
    const bool stalled = !history.empty() && history.back() - e <= kStopFraction * history.back();
    history.push_back(e);
    if (e == 0.0 || stalled) break;
  }
  return cluster;
}

// The points floor(i P / S), i = 0 .. S - 1, copied point-major.
std::vector<float> strided_subset(const float* x, std::size_t P, std::size_t D, std::size_t S) {
  std::vector<float> subset(S * D);
  for (std::size_t i = 0; i < S; ++i) {
    const std::size_t p = i * (P / S) + (i * (P % S)) / S;  // floor(i P / S) without overflow (i, P % S < S)
    std::copy(x + p * D, x + (p + 1) * D, subset.begin() + static_cast<std::ptrdiff_t>(i * D));
  }
  return subset;
}

}  // namespace

CpcaResult cpca(const float* x, std::size_t P, std::size_t D, const CpcaOptions& o, const std::string& what) {
  validate_cpca_options(P, D, o, what);
  ScopedFlushDenormals flush;
  CpcaResult r;
  const bool subset = o.fit_points > 0 && P > o.fit_points;
  Model m;
  std::vector<std::uint32_t> cluster;
  if (subset) {
    const std::vector<float> points = strided_subset(x, P, D, o.fit_points);
    m = seed_model(points.data(), o.fit_points, D, o);
    fit_rounds(points.data(), o.fit_points, o, m, r.error_history);
    std::vector<double> error;  // every point: assign, fill, refit on all members, assign again
    assign(x, P, m, o.threads, cluster, error);
    fill_empty_clusters(x, P, m, cluster, error);
    refit(x, cluster, o.seed, static_cast<int>(r.error_history.size()), o.threads, m);
    assign(x, P, m, o.threads, cluster, error);
  } else {
    m = seed_model(x, P, D, o);
    cluster = fit_rounds(x, P, o, m, r.error_history);
  }
  std::vector<double> weights(P * static_cast<std::size_t>(o.pca));
  r.error = total_error(x, P, m, cluster, o.threads, &weights);
  r.dimension = D;
  r.count = P;
  r.clusters = o.clusters;
  r.pca = o.pca;
  r.means.assign(m.mean.begin(), m.mean.end());
  r.bases.assign(m.basis.begin(), m.basis.end());
  r.cluster = std::move(cluster);
  r.weights.assign(weights.begin(), weights.end());
  return r;
}

}  // namespace prt::compress
