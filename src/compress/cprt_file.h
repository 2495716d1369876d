#pragma once
// Compressed transfer files (.cprt): a CompressedTransfer (compressed.h) on disk. Binary layout in
// docs/formats.md ("Compressed transfer files"); this header is the reader and writer.
#include <memory>
#include <string>

#include "compress/compressed.h"

namespace prt::compress {

/// The first 8 bytes of every .cprt file.
inline constexpr char kCprtMagic[8] = {'P', 'R', 'T', 'C', 'P', 'C', 'A', '\0'};

/// Writes atomically (temporary file + rename). Throws prt::Error naming the file if the model is
/// inconsistent (sizes, ranges) or writing fails.
void write_cprt(const std::string& path, const CompressedTransfer& compressed);

/// Reads the header only (arrays and per-cluster errors left empty): every field is checked before
/// anything is allocated; throws prt::Error("<path>: <problem>") naming the damage.
CompressedTransfer read_cprt_header(const std::string& path);

/// Reads and checks the whole file: header, sizes, payload checksum, cluster ids < K, finite values.
CompressedTransfer read_cprt(const std::string& path);

/// Payload bytes of the .cprt file of `compressed` (means, directions, weights, ids, per-cluster errors).
std::uint64_t payload_bytes(const CompressedTransfer& compressed);

/// Multi-line description for `prt info`: the source transfer, K, N, iterations, sizes and errors.
std::string describe(const CompressedTransfer& compressed);

/// True if the file at `path` starts with kCprtMagic (false if it is shorter). Throws Error, as every
/// reader does (open_input), if `path` is not a readable regular file.
bool is_cprt_file(const std::string& path);

/// (Reading any transfer file, .prt or .cprt: compress/open_transfer.h.)

}  // namespace prt::compress
