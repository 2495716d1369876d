#pragma once
// The up-front memory check of commands whose memory grows with an option (a lightmap size, a probe
// grid, bands, an image size): estimate the bytes from the options, refuse at once if they cannot fit,
// rather than allocate for minutes and then run out.
#include <cstdint>
#include <string>

namespace prt {

/// This machine's physical memory in bytes (sysconf).
std::uint64_t physical_memory_bytes();

/// Throws OptionError(field, " <value>: needs about X GiB, more than 80% of this machine's Y GiB") if
/// `need_bytes` exceeds 80% of `available_bytes` (physical_memory_bytes() when 0). `field` names the
/// option that sized it and `value` its value (e.g. "grid", "4096,4096,4 at 16 bands").
void check_memory_need(const std::string& field, const std::string& value, std::uint64_t need_bytes,
                       std::uint64_t available_bytes = 0);

/// a * b, or UINT64_MAX where the product does not fit (estimates saturate rather than wrap).
std::uint64_t saturating_product(std::uint64_t a, std::uint64_t b);

}  // namespace prt
