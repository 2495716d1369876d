#pragma once
// Large float buffers that are filled at once (a lightmap's transfer grid, a denoiser's copy): their
// pages are asked for as transparent huge pages (Linux madvise MADV_HUGEPAGE; the kernel's
// /sys/kernel/mm/transparent_hugepage/enabled "madvise" or "always"), so that the first write faults
// once per 2 MiB instead of once per 4 KiB. The values are those of std::vector::assign; only the
// cost of the first touch changes (about 40% of the denoiser's CPU time on a 1024 x 1024 lightmap on
// a 2-core virtual machine, docs/performance.md). Elsewhere, or under the size where it pays, a plain
// assign.
#include <cstddef>
#include <vector>

namespace prt {

/// Buffers of at least this many bytes are advised (smaller ones hold at most one huge page).
constexpr std::size_t kBigBufferBytes = std::size_t(4) << 20;

/// Asks the kernel to back the whole 2 MiB-aligned pages inside [data, data + bytes) with huge pages;
/// call before the first write. No effect where unsupported or under kBigBufferBytes.
void advise_huge_pages(void* data, std::size_t bytes);

/// v = count copies of value, in new storage advised as huge pages where v's capacity is short.
template <class T>
void assign_big(std::vector<T>& v, std::size_t count, const T& value) {
  if (count * sizeof(T) >= kBigBufferBytes && v.capacity() < count) {
    std::vector<T> fresh;
    fresh.reserve(count);  // allocated, not yet written
    advise_huge_pages(fresh.data(), count * sizeof(T));
    v.swap(fresh);
  }
  v.assign(count, value);
}

/// A copy of `source` in storage advised as huge pages.
template <class T>
std::vector<T> copy_big(const std::vector<T>& source) {
  std::vector<T> out;
  out.reserve(source.size());
  if (source.size() * sizeof(T) >= kBigBufferBytes) advise_huge_pages(out.data(), source.size() * sizeof(T));
  out.assign(source.begin(), source.end());
  return out;
}

}  // namespace prt
