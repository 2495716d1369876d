#pragma once
// Exchanging per-item results between the ranks of a job (docs/distributed.md). Results are stored by
// item index: item i owns values[i * per_item .. (i + 1) * per_item). Items are visited in `order`
// (a permutation of 0..N-1, or nullptr for 0..N-1 itself) and split by partition(N, size, rank): this
// rank has computed the items order[k] for k in its range; the others hold anything there.
// Rows travel as raw bytes, so every value arrives bit for bit.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "dist/context.h"
#include "dist/partition.h"

namespace prt::dist {

/// This rank's range of positions in the visiting order of `count` items.
inline Range my_range(const Context& context, std::size_t count) {
  return partition(count, context.size(), context.rank());
}

/// Byte-level form of allgather_items (row_bytes per item, `values` holds count rows).
void allgather_item_bytes(const Context& context, void* values, std::size_t count, std::size_t row_bytes,
                          const std::vector<std::uint32_t>* order);
/// Byte-level form of gather_items.
void gather_item_bytes(const Context& context, void* values, std::size_t count, std::size_t row_bytes,
                       const std::vector<std::uint32_t>* order);

/// After the call every rank holds every item's row (each computed by its owner). A no-op on one rank.
template <class T>
void allgather_items(const Context& context, std::vector<T>& values, std::size_t per_item,
                     const std::vector<std::uint32_t>* order = nullptr) {
  if (context.size() == 1 || per_item == 0) return;
  allgather_item_bytes(context, values.data(), values.size() / per_item, per_item * sizeof(T), order);
}

/// After the call rank 0 holds every item's row; the other ranks' `values` are unchanged.
template <class T>
void gather_items(const Context& context, std::vector<T>& values, std::size_t per_item,
                  const std::vector<std::uint32_t>* order = nullptr) {
  if (context.size() == 1 || per_item == 0) return;
  gather_item_bytes(context, values.data(), values.size() / per_item, per_item * sizeof(T), order);
}

}  // namespace prt::dist
