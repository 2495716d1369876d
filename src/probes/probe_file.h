#pragma once
// prt's own probe file (`--format prt`, extension .prtprobes): a JSON header plus a binary payload in
// one file. probes/prt/README.md is the full specification; in short:
//
//   offset 0   8 bytes   magic "PRTPROBE"
//   offset 8   uint32 LE format version (1)
//   offset 12  uint32 LE header length H in bytes (a multiple of 8)
//   offset 16  H bytes   UTF-8 JSON object, padded with spaces to H bytes
//   offset 16+H          payload: the arrays the header's "arrays" list names, each at its "offset"
//                        (bytes from the start of the payload, a multiple of 8), little-endian
//
// Header keys (written in this order): "format": "prt-probes", "version": 1, "bands", "basis"
// ("real-orthonormal-condon-shortley"), "index" ("l*(l+1)+m"), "frame" ("right-handed, +Y up"),
// "quantity" ("incident radiance"), "units" (positions: scene units; radiance: the environment's
// linear units), "count", "valid_count", "layout" ({"type": "grid", "counts": [NX,NY,NZ],
// "bounds": [[x0,y0,z0],[x1,y1,z1]], "order": ..., "position": "cell centres"} or {"type": "points"}),
// "sky" (bands^2 [r,g,b]: environment + sun, unoccluded), "transfer" (absent, or {"bands", "channels",
// "environment": [[r,g,b],...]}), "parameters" (the bake's options), "arrays" (list of {"name", "type",
// "shape", "offset", "bytes"}), "payload_bytes", "payload_fnv1a64" (16 hex digits).
// Arrays: "positions" float32 [N,3]; "coefficients" float32 [N, bands^2, 3]; "valid" uint8 [N];
// "backface_fraction" float32 [N]; with transfer also "transfer" float32 [N, channels, bands^2,
// transfer_bands^2] and "transfer_bias" float32 [N, bands^2, 3].
#include <string>

#include "probes/probe_set.h"

namespace prt::probes {

/// The file's bytes for `probes`. Throws prt::Error (check_probe_set) for an inconsistent set.
std::string format_probe_file(const ProbeSet& probes);

/// Writes the file atomically.
void write_probe_file(const std::string& path, const ProbeSet& probes);

/// Reads and checks a probe file: magic, version, header JSON and every key it needs, array names,
/// types, shapes, offsets and sizes against the header, the payload checksum, finite values. Throws
/// prt::Error("<path>: <problem>") naming what is wrong (truncated, wrong magic, unsupported version,
/// checksum mismatch, ...).
ProbeSet read_probe_file(const std::string& path);

/// Parses the bytes of a probe file (as read_probe_file does); `name` is used in messages.
ProbeSet parse_probe_file(const std::string& bytes, const std::string& name);

}  // namespace prt::probes
