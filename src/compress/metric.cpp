#include "compress/metric.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

#include "core/error.h"

namespace prt::compress {

namespace {

using MatrixD = Eigen::MatrixXd;

// A block before the square root: the values at `index` and their symmetric quadratic form.
struct RawBlock {
  std::vector<std::uint32_t> index;
  MatrixD a;
};

// Per colour (0..2): the sections' cross spectra, S_c(a, b) at band l: spectra[(a * sections + b)][l * 3 + c].
using CrossSpectra = std::vector<std::vector<double>>;

CrossSpectra cross_spectra(const transfer::Header& h, int sections, const MetricLighting& lighting) {
  const int bands = static_cast<int>(h.bands);
  const std::vector<double> flat(static_cast<std::size_t>(bands) * 3, 1.0), zero(flat.size(), 0.0);
  CrossSpectra s(static_cast<std::size_t>(sections * sections));
  const sh::RgbCoefficients* source[2] = {lighting.sky, lighting.discs};
  for (int a = 0; a < sections; ++a)
    for (int b = 0; b < sections; ++b) {
      std::vector<double>& out = s[static_cast<std::size_t>(a * sections + b)];
      if (!lighting.sky) out = a == b ? flat : zero;  // flat, independent sections
      else if (!lighting.discs && sections == 2) out = a == b ? rotation_averaged_spectrum(*lighting.sky, bands) : zero;
      else out = rotation_averaged_cross_spectrum(*source[a], *source[b], bands);
    }
  return s;
}

// One block per (transfer channel, lighting coefficient j): the g = rows values of that column in every
// section (diffuse: rows = 1), with form sum over the colours reading the channel of kron(S_c, gram_c).
std::vector<RawBlock> metric_blocks(const transfer::Header& h, int sections, const CrossSpectra& s, const MatrixD* gram) {
  const int n_in = static_cast<int>(h.bands * h.bands);
  const bool glossy = transfer::is_glossy(h.kind);
  const int rows = glossy ? static_cast<int>(h.bands_out * h.bands_out) : 1;
  const std::size_t D = static_cast<std::size_t>(h.values_per_vertex());
  std::vector<RawBlock> blocks;
  for (int c = 0; c < static_cast<int>(h.channels); ++c)
    for (int j = 0; j < n_in; ++j) {
      const std::size_t l = static_cast<std::size_t>(std::sqrt(static_cast<double>(j)));
      RawBlock block{{}, MatrixD::Zero(sections * rows, sections * rows)};
      for (int a = 0; a < sections; ++a)
        for (int k = 0; k < rows; ++k)
          block.index.push_back(static_cast<std::uint32_t>(static_cast<std::size_t>(a) * D + static_cast<std::size_t>((c * rows + k) * n_in + j)));
      for (int colour = 0; colour < 3; ++colour) {
        if (h.channels != 1 && colour != c) continue;
        for (int a = 0; a < sections; ++a)
          for (int b = 0; b < sections; ++b)
            block.a.block(a * rows, b * rows, rows, rows) += s[static_cast<std::size_t>(a * sections + b)][l * 3 + colour] * gram[colour];
      }
      blocks.push_back(std::move(block));
    }
  return blocks;
}

std::vector<double> row_major(const MatrixD& m) {
  std::vector<double> out(static_cast<std::size_t>(m.size()));
  for (Eigen::Index r = 0; r < m.rows(); ++r)
    for (Eigen::Index c = 0; c < m.cols(); ++c) out[static_cast<std::size_t>(r * m.cols() + c)] = m(r, c);
  return out;
}

}  // namespace

std::vector<double> rotation_averaged_cross_spectrum(const sh::RgbCoefficients& a, const sh::RgbCoefficients& b, int bands) {
  std::vector<double> s(static_cast<std::size_t>(bands) * 3, 0.0);
  for (int l = 0; l < bands; ++l)
    for (int m = -l; m <= l; ++m) {
      const std::size_t j = static_cast<std::size_t>(l * (l + 1) + m);
      if (j >= a.values.size() || j >= b.values.size()) continue;
      for (int c = 0; c < 3; ++c) s[static_cast<std::size_t>(l) * 3 + c] += a.values[j][c] * b.values[j][c] / (2 * l + 1);
    }
  return s;
}

std::vector<double> rotation_averaged_spectrum(const sh::RgbCoefficients& lighting, int bands) {
  return rotation_averaged_cross_spectrum(lighting, lighting, bands);
}

Metric shaded_metric(const transfer::Header& h, int sections, const MetricLighting& lighting, const brdf::BrdfMatrix* brdf) {
  if (brdf) return shaded_metric(h, sections, lighting, std::vector<brdf::BrdfMatrix>{*brdf}, {1.0});
  return shaded_metric(h, sections, lighting, std::vector<brdf::BrdfMatrix>{}, {});
}

Metric shaded_metric(const transfer::Header& h, int sections, const MetricLighting& lighting, const std::vector<brdf::BrdfMatrix>& brdfs,
                     const std::vector<double>& shares) {
  if (sections != 1 && sections != 2) fail("compression metric: 1 or 2 sections, not " + std::to_string(sections));
  if (brdfs.size() != shares.size()) fail("compression metric: " + std::to_string(brdfs.size()) + " BRDFs, " + std::to_string(shares.size()) + " shares");
  Metric metric;
  metric.dimension = static_cast<std::size_t>(h.values_per_vertex()) * static_cast<std::size_t>(sections);
  const bool glossy = transfer::is_glossy(h.kind);
  if (!glossy && !lighting.sky) return metric;
  if (glossy && brdfs.empty()) fail("compression metric: glossy transfer needs its BRDF matrix");
  MatrixD gram[3] = {MatrixD::Ones(1, 1), MatrixD::Ones(1, 1), MatrixD::Ones(1, 1)};  // sum_k share_k B_kc^T B_kc per colour
  if (glossy) {
    const int n_out = static_cast<int>(h.bands_out * h.bands_out);
    for (int colour = 0; colour < 3; ++colour) gram[colour] = MatrixD::Zero(n_out, n_out);
    for (std::size_t k = 0; k < brdfs.size(); ++k) {
      if (brdfs[k].bands != static_cast<int>(h.bands_out))
        fail("compression metric: the BRDF matrix has " + std::to_string(brdfs[k].bands) + " bands, the transfer's output has " +
             std::to_string(h.bands_out));
      for (int colour = 0; colour < 3; ++colour) {
        const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> b(brdfs[k].for_colour(colour), n_out, n_out);
        gram[colour] += shares[k] * (b.transpose() * b);
      }
    }
  }
  std::vector<RawBlock> raw = metric_blocks(h, sections, cross_spectra(h, sections, lighting), gram);
  std::vector<Eigen::SelfAdjointEigenSolver<MatrixD>> eigen;
  double largest = 0.0;
  for (const RawBlock& block : raw) {
    eigen.emplace_back(block.a);
    largest = std::max(largest, eigen.back().eigenvalues().maxCoeff());
  }
  if (!(largest > 0.0)) fail("compression metric: the lighting has no energy in the transfer's bands");
  metric.identity = false;
  for (std::size_t i = 0; i < raw.size(); ++i) {
    const Eigen::VectorXd value = eigen[i].eigenvalues().cwiseMax(kMetricFloor * largest).cwiseSqrt();
    const MatrixD& v = eigen[i].eigenvectors();
    metric.blocks.push_back({std::move(raw[i].index), row_major(v * value.asDiagonal() * v.transpose()),
                             row_major(v * value.cwiseInverse().asDiagonal() * v.transpose())});
  }
  return metric;
}

void apply_metric(const Metric& metric, const float* in, float* out, std::size_t count, bool inverse) {
  const std::size_t D = metric.dimension;
  if (metric.identity) {
    if (in != out) std::copy(in, in + count * D, out);
    return;
  }
  std::vector<double> x, y;
  for (std::size_t p = 0; p < count; ++p) {
    const float* src = in + p * D;
    float* dst = out + p * D;
    for (const Metric::Block& block : metric.blocks) {
      const std::size_t g = block.index.size();
      const std::vector<double>& m = inverse ? block.inverse : block.forward;
      x.resize(g);
      y.assign(g, 0.0);
      for (std::size_t i = 0; i < g; ++i) x[i] = src[block.index[i]];
      for (std::size_t r = 0; r < g; ++r)
        for (std::size_t i = 0; i < g; ++i) y[r] += m[r * g + i] * x[i];
      for (std::size_t r = 0; r < g; ++r) dst[block.index[r]] = static_cast<float>(y[r]);
    }
  }
}

}  // namespace prt::compress
