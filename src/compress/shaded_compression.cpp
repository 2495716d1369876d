#include "compress/shaded_compression.h"

#include "compress/metric.h"
#include "light/disc.h"

namespace prt::compress {

CompressedTransfer compress_for_shading(const transfer::TransferData& transfer, const std::string& what,
                                        const CompressionRequest& request) {
  const transfer::Header& h = transfer.header;
  validate_cpca_options(point_blocks(h, transfer.coverage).size(), static_cast<std::size_t>(h.values_per_vertex()),
                        request.options, what);
  const light::SceneLighting* lighting = request.lighting;
  sh::RgbCoefficients discs;
  MetricLighting metric_lighting{request.metric_sky, nullptr};  // flat spectrum unless one is given
  if (lighting) {
    discs = light::discs_coefficients(static_cast<int>(h.bands), lighting->discs);
    metric_lighting = {&lighting->sky, lighting->discs.empty() ? nullptr : &discs};
  }
  Metric metric;
  if (request.shaded_metric) metric = transfer_metric(transfer, metric_lighting, what);
  CompressedTransfer c = compress_transfer(transfer, request.options, request.scalar, what,
                                           request.shaded_metric ? &metric : nullptr);
  if (lighting) add_radiance_error(c, transfer, lighting->sky, what, &discs);
  return c;
}

}  // namespace prt::compress
