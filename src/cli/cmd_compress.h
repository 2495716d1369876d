#pragma once
// What `prt compress` and `prt bake --compress K,N` share: compress a transfer in memory (with the
// optional shaded-radiance error) and print the summary.
#include <string>

#include "compress/compressed.h"

namespace prt::cli {

struct CompressionRequest {
  compress::CpcaOptions options;
  transfer::Scalar scalar = transfer::Scalar::float32;
  std::string lighting;  ///< environment image or SH lighting JSON for the radiance error; empty = none
  int threads = 0;
  /// Fit in the shaded-radiance metric (compress/metric.h: the lighting's rotation-averaged spectrum
  /// if `lighting` is given, and for glossy the baked BRDF); false: plain L2 of the transfer values.
  bool shaded_metric = true;
};

/// Validates K and N against the transfer (one-line errors naming `what`), compresses (in the metric
/// the request names), adds the radiance error under request.lighting if given.
compress::CompressedTransfer compress_for_cli(const transfer::TransferData& transfer, const std::string& what,
                                              const CompressionRequest& request);

/// The summary on stderr: sizes, iterations, time, errors.
void report_compression(const compress::CompressedTransfer& compressed, double seconds, const std::string& output);

/// Parses "K,N" (two integers); false if the text is not of that form.
bool parse_compress_setting(const std::string& text, int& clusters, int& pca);

}  // namespace prt::cli
