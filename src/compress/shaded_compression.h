#pragma once
// Compression as prt compress and prt bake --compress run it: clustered PCA fitted in the metric of the
// radiance the transfer shades, with the error under a given lighting reported beside it.
#include <string>

#include "compress/compressed.h"
#include "light/scene_lighting.h"

namespace prt::compress {

struct CompressionRequest {
  CpcaOptions options;
  transfer::Scalar scalar = transfer::Scalar::float32;  ///< of the stored means, directions and weights
  /// The lighting to fit to and report the shaded error under, split as shading splits it (its sky's SH
  /// meets the transfer, its discs' SH the bounce-only part; docs/conventions.md, "Sun and sky"), with
  /// as many bands as the transfer; null: no lighting (the shaded metric then averages over all skies).
  const light::SceneLighting* lighting = nullptr;
  /// Without `lighting`: the SH whose rotation-averaged spectrum the shaded metric is fitted to (e.g.
  /// the ship default's prior, ship_defaults.h); null: a flat spectrum. No error is reported under it.
  const sh::RgbCoefficients* metric_sky = nullptr;
  /// Fit in the shaded-radiance metric (compress/metric.h; glossy through the baked BRDF); false: the
  /// plain L2 of the transfer values.
  bool shaded_metric = true;
};

/// Checks the request's cluster and PCA counts against the transfer (OptionError naming the field and
/// `what`), compresses in the metric the request names, and adds the radiance error under
/// request.lighting when given. `what` names the transfer in messages (its file).
CompressedTransfer compress_for_shading(const transfer::TransferData& transfer, const std::string& what,
                                        const CompressionRequest& request);

}  // namespace prt::compress
