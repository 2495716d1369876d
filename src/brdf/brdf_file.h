#pragma once
// BRDF matrix files, written by `prt brdf` (docs/formats.md, "BRDF matrix files").
//
// JSON (.json): an object
//   {"format": "prt-brdf-matrix", "version": 1, "brdf": SPEC, "bands": N, "channels": C,
//    "layout": "...", "matrix": [ channel 0: [ row 0: [N^2 numbers], ..., row N^2-1 ], ... ]}
// with matrix[c][k][j] = B_kj of channel c (row k = outgoing coefficient, column j = incident one,
// flat SH index l(l+1)+m), numbers with 17 significant digits (round-trips doubles exactly).
//
// Binary (.bin), little-endian:
//   offset 0   8 bytes  magic "PRTBRDF1"
//   offset 8   u32      bands N (1..32)
//   offset 12  u32      channels C (1 or 3)
//   offset 16  u32      length S of the BRDF spec in bytes
//   offset 20  u32      0 (reserved)
//   offset 24  S bytes  the canonical SPEC string (UTF-8, no terminator)
//   then       C N^4 float64 values, channel-major, then row-major [out k][in j]
// and nothing after them.
#include <string>

#include "brdf/projection.h"

namespace prt::brdf {

/// Writes `matrix` atomically as .json or .bin (by the extension; any case). Throws prt::Error naming
/// the file for another extension or a failed write.
void write_brdf_matrix(const std::string& path, const BrdfMatrix& matrix);

/// Reads a file written by write_brdf_matrix. Throws prt::Error("<path>: <problem>") for a wrong magic
/// or format, bands or channels out of range, or a size that does not match.
BrdfMatrix read_brdf_matrix(const std::string& path);

}  // namespace prt::brdf
