#include "compress/compressed.h"

#include <cmath>

#include "brdf/projection.h"
#include "core/error.h"
#include "shade/glossy.h"
#include "shade/shade.h"
#include "transfer/half.h"

namespace prt::compress {

namespace {

void round_to(std::vector<float>& values, transfer::Scalar scalar) {
  if (scalar != transfer::Scalar::float16) return;
  for (float& v : values) v = transfer::half_to_float(transfer::float_to_half(v));
}

// Reconstruction of vertex p into out[0, D), accumulated in double in a fixed order.
void reconstruct(const CompressedTransfer& c, std::size_t p, float* out) {
  const std::size_t D = c.dimension(), N = static_cast<std::size_t>(c.pca), k = c.cluster[p];
  const float* mean = &c.means[k * D];
  const float* w = &c.weights[p * N];
  for (std::size_t i = 0; i < D; ++i) {
    double s = mean[i];
    for (std::size_t n = 0; n < N; ++n) s += static_cast<double>(w[n]) * c.bases[(k * N + n) * D + i];
    out[i] = static_cast<float>(s);
  }
}

// Adds |a - b|^2 and |b|^2 over `floats` values to the sums of cluster k and to the total.
void add_squares(const float* a, const float* b, std::size_t floats, std::uint32_t k, double ErrorSums::*error2,
                 double ErrorSums::*norm2, CompressedTransfer& c) {
  double e = 0.0, n = 0.0;
  for (std::size_t i = 0; i < floats; ++i) {
    e += (static_cast<double>(a[i]) - b[i]) * (static_cast<double>(a[i]) - b[i]);
    n += static_cast<double>(b[i]) * b[i];
  }
  ErrorSums& s = c.per_cluster[k];
  s.*error2 += e;
  s.*norm2 += n;
  c.total.*error2 += e;
  c.total.*norm2 += n;
}

}  // namespace

double ErrorSums::transfer_relative() const { return transfer_norm2 > 0.0 ? std::sqrt(transfer_error2 / transfer_norm2) : 0.0; }
double ErrorSums::radiance_relative() const { return radiance_norm2 > 0.0 ? std::sqrt(radiance_error2 / radiance_norm2) : 0.0; }

CompressedTransfer compress_transfer(const transfer::TransferData& transfer, const CpcaOptions& options, transfer::Scalar scalar,
                                     const std::string& what) {
  const std::size_t P = static_cast<std::size_t>(transfer.header.vertex_count);
  const std::size_t D = static_cast<std::size_t>(transfer.header.values_per_vertex());
  if (transfer.values.size() != P * D) fail_file(what, "internal: value count does not match the header");
  CpcaResult r = cpca(transfer.values.data(), P, D, options, what);
  CompressedTransfer c;
  c.source = transfer.header;
  c.source.scalar = scalar;
  c.clusters = r.clusters;
  c.pca = r.pca;
  c.iterations = static_cast<int>(r.error_history.size());
  c.means = std::move(r.means);
  c.bases = std::move(r.bases);
  c.cluster = std::move(r.cluster);
  c.weights = std::move(r.weights);
  round_to(c.means, scalar);
  round_to(c.bases, scalar);
  round_to(c.weights, scalar);
  c.per_cluster.assign(static_cast<std::size_t>(c.clusters), ErrorSums{});
  std::vector<float> block(D);
  for (std::size_t p = 0; p < P; ++p) {
    reconstruct(c, p, block.data());
    add_squares(block.data(), &transfer.values[p * D], D, c.cluster[p], &ErrorSums::transfer_error2, &ErrorSums::transfer_norm2, c);
  }
  return c;
}

transfer::TransferData decompress(const CompressedTransfer& c) {
  transfer::TransferData t;
  t.header = c.source;
  t.header.scalar = transfer::Scalar::float32;
  const std::size_t P = c.cluster.size(), D = c.dimension();
  t.values.resize(P * D);
  for (std::size_t p = 0; p < P; ++p) reconstruct(c, p, &t.values[p * D]);
  return t;
}

void add_radiance_error(CompressedTransfer& c, const transfer::TransferData& original, const sh::RgbCoefficients& lighting,
                        const std::string& what) {
  const transfer::TransferData approximate = decompress(c);
  for (ErrorSums& s : c.per_cluster) s.radiance_error2 = s.radiance_norm2 = 0.0;
  c.total.radiance_error2 = c.total.radiance_norm2 = 0.0;
  std::vector<glm::vec3> test, reference;
  std::size_t stride = 1;
  if (transfer::is_glossy(original.header.kind)) {
    const brdf::BrdfMatrix b = brdf::project(shade::baked_brdf(original.header, what), static_cast<int>(original.header.bands_out));
    test = shade::glossy_outgoing_coefficients(approximate, b, lighting);
    reference = shade::glossy_outgoing_coefficients(original, b, lighting);
    stride = static_cast<std::size_t>(original.header.bands_out) * original.header.bands_out;
  } else {
    test = shade::shade_diffuse(approximate, lighting);
    reference = shade::shade_diffuse(original, lighting);
  }
  for (std::size_t p = 0; p < c.cluster.size(); ++p)
    add_squares(&test[p * stride].x, &reference[p * stride].x, 3 * stride, c.cluster[p], &ErrorSums::radiance_error2, &ErrorSums::radiance_norm2, c);
  c.has_radiance_error = true;
}

std::uint64_t uncompressed_bytes(const transfer::Header& header, transfer::Scalar scalar) {
  return header.vertex_count * header.values_per_vertex() * (scalar == transfer::Scalar::float16 ? 2 : 4);
}

}  // namespace prt::compress
