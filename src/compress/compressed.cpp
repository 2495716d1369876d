#include "compress/compressed.h"

#include <algorithm>
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

namespace {

// The points CPCA sees: each point block's values (and bounce-only values), then G applied. Empty when
// the transfer's values can be used as they are (per vertex, one section, no metric).
std::vector<float> gather_points(const transfer::TransferData& t, const std::vector<std::size_t>& blocks, const Metric* metric,
                                 std::size_t D, std::size_t E) {
  const bool weighted = metric && !metric->identity, bounce = E != D;
  std::vector<float> points;
  if (!bounce && !weighted && !t.header.is_texel()) return points;
  points.resize(blocks.size() * E);
  for (std::size_t p = 0; p < blocks.size(); ++p) {
    std::copy_n(&t.values[blocks[p] * D], D, &points[p * E]);
    if (bounce) std::copy_n(&t.bounce_only[blocks[p] * D], D, &points[p * E + D]);
  }
  if (weighted) apply_metric(*metric, points.data(), points.data(), blocks.size(), false);
  return points;
}

}  // namespace

CompressedTransfer compress_transfer(const transfer::TransferData& transfer, const CpcaOptions& options, transfer::Scalar scalar,
                                     const std::string& what, const Metric* metric) {
  const transfer::Header& h = transfer.header;
  const std::size_t D = static_cast<std::size_t>(h.values_per_vertex());
  if (transfer.values.size() != h.block_count() * D) fail_file(what, "internal: value count does not match the header");
  if (h.is_texel() && transfer.coverage.size() != h.block_count()) fail_file(what, "internal: coverage mask does not match the header");
  const bool bounce = !transfer.bounce_only.empty();
  if (bounce && transfer.bounce_only.size() != transfer.values.size()) fail_file(what, "internal: bounce-only value count does not match the header");
  const std::vector<std::size_t> blocks = point_blocks(h, transfer.coverage);
  const std::size_t P = blocks.size(), E = bounce ? 2 * D : D;  // points, values per point
  const bool weighted = metric && !metric->identity;
  if (metric && metric->dimension != E) fail_file(what, "internal: the compression metric does not match the transfer");
  validate_cpca_options(P, D, options, what);  // N is bounded by the transfer's D, before the work
  const std::vector<float> points = gather_points(transfer, blocks, metric, D, E);
  CpcaResult r = cpca(points.empty() ? transfer.values.data() : points.data(), P, E, options, what);
  if (weighted) {
    apply_metric(*metric, r.means.data(), r.means.data(), static_cast<std::size_t>(r.clusters), true);
    apply_metric(*metric, r.bases.data(), r.bases.data(), static_cast<std::size_t>(r.clusters) * r.pca, true);
  }
  CompressedTransfer c;
  c.bounce = bounce;
  c.source = h;
  c.source.scalar = scalar;
  c.coverage = transfer.coverage;
  c.texel_points = h.is_texel() ? P : 0;
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
  std::vector<float> block(E);
  for (std::size_t p = 0; p < P; ++p) {  // the transfer's values (the bounce-only part is a part of them)
    reconstruct_point(c, p, block.data());
    add_squares(block.data(), &transfer.values[blocks[p] * D], D, c.cluster[p], &ErrorSums::transfer_error2, &ErrorSums::transfer_norm2, c);
  }
  return c;
}

namespace {

// A glossy transfer's BRDF matrices (at its output bands) and each vertex's index (shade::baked_brdfs).
struct BakedMatrices {
  std::vector<brdf::BrdfMatrix> matrices;
  std::vector<std::uint32_t> vertex;
};

BakedMatrices baked_matrices(const transfer::Header& h, const std::string& what) {
  const brdf::VertexBrdfs brdfs = shade::baked_brdfs(h, what);
  BakedMatrices out;
  for (const brdf::Brdf& b : brdfs.table) out.matrices.push_back(brdf::project(b, static_cast<int>(h.bands_out)));
  out.vertex = brdfs.vertex;
  return out;
}

}  // namespace

Metric transfer_metric(const transfer::TransferData& transfer, const MetricLighting& lighting, const std::string& what) {
  const transfer::Header& h = transfer.header;
  const int sections = transfer.bounce_only.empty() ? 1 : 2;
  if (!transfer::is_glossy(h.kind)) return shaded_metric(h, sections, lighting, nullptr);
  const BakedMatrices baked = baked_matrices(h, what);
  std::vector<double> shares(baked.matrices.size(), baked.vertex.empty() ? 1.0 : 0.0);
  for (const std::uint32_t k : baked.vertex) shares[k] += 1.0 / static_cast<double>(baked.vertex.size());
  return shaded_metric(h, sections, lighting, baked.matrices, shares);
}

void add_radiance_error(CompressedTransfer& c, const transfer::TransferData& original, const sh::RgbCoefficients& sky,
                        const std::string& what, const sh::RgbCoefficients* discs) {
  const transfer::TransferData approximate = decompress(c);
  for (ErrorSums& s : c.per_cluster) s.radiance_error2 = s.radiance_norm2 = 0.0;
  c.total.radiance_error2 = c.total.radiance_norm2 = 0.0;
  const bool glossy = transfer::is_glossy(original.header.kind);
  const BakedMatrices baked = glossy ? baked_matrices(original.header, what) : BakedMatrices{};
  // What the transfer (or, `bounce`, its bounce-only part) shades under `lighting`, each vertex with its BRDF.
  const auto shaded = [&](const transfer::TransferData& t, bool bounce, const sh::RgbCoefficients& lighting) {
    transfer::TransferData part;
    if (bounce) part.header = t.header, part.values = t.bounce_only;
    const transfer::TransferData& used = bounce ? part : t;
    return glossy ? shade::glossy_outgoing_coefficients(used, baked.matrices, baked.vertex, lighting) : shade::shade_diffuse(used, lighting);
  };
  std::vector<glm::vec3> test = shaded(approximate, false, sky), reference = shaded(original, false, sky);
  if (discs && !original.bounce_only.empty() && c.bounce) {
    const std::vector<glm::vec3> test_bounce = shaded(approximate, true, *discs), reference_bounce = shaded(original, true, *discs);
    for (std::size_t i = 0; i < test.size(); ++i) test[i] += test_bounce[i], reference[i] += reference_bounce[i];
  }
  const std::size_t stride = glossy ? static_cast<std::size_t>(original.header.bands_out) * original.header.bands_out : 1;
  const std::vector<std::size_t> blocks = point_blocks(c.source, c.coverage);
  for (std::size_t p = 0; p < blocks.size(); ++p)
    add_squares(&test[blocks[p] * stride].x, &reference[blocks[p] * stride].x, 3 * stride, c.cluster[p], &ErrorSums::radiance_error2,
                &ErrorSums::radiance_norm2, c);
  c.has_radiance_error = true;
}

}  // namespace prt::compress
