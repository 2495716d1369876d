#include "dist/exchange.h"

#include <cstring>

namespace prt::dist {

namespace {

std::size_t item_at(const std::vector<std::uint32_t>* order, std::size_t k) { return order ? (*order)[k] : k; }

std::vector<std::size_t> row_counts(std::size_t count, int ranks) {
  std::vector<std::size_t> counts;
  for (const Range& r : partitions(count, ranks)) counts.push_back(r.size());
  return counts;
}

// This rank's rows, in visiting order.
std::vector<unsigned char> pack_mine(const Context& context, const unsigned char* values, std::size_t count,
                                     std::size_t row_bytes, const std::vector<std::uint32_t>* order) {
  const Range mine = my_range(context, count);
  std::vector<unsigned char> packed(mine.size() * row_bytes);
  for (std::size_t k = mine.begin; k < mine.end; ++k)
    std::memcpy(packed.data() + (k - mine.begin) * row_bytes, values + item_at(order, k) * row_bytes, row_bytes);
  return packed;
}

// Every rank's rows (in visiting order) back to their items; this rank's own are already in place.
void unpack_others(const Context& context, const std::vector<unsigned char>& all, unsigned char* values, std::size_t count,
                   std::size_t row_bytes, const std::vector<std::uint32_t>* order) {
  const Range mine = my_range(context, count);
  for (std::size_t k = 0; k < count; ++k)
    if (k < mine.begin || k >= mine.end) std::memcpy(values + item_at(order, k) * row_bytes, all.data() + k * row_bytes, row_bytes);
}

}  // namespace

void allgather_item_bytes(const Context& context, void* values, std::size_t count, std::size_t row_bytes,
                          const std::vector<std::uint32_t>* order) {
  auto* bytes = static_cast<unsigned char*>(values);
  const std::vector<unsigned char> packed = pack_mine(context, bytes, count, row_bytes, order);
  std::vector<unsigned char> all(count * row_bytes);
  context.allgather_rows(packed.data(), packed.size() / row_bytes, row_bytes, all.data(), row_counts(count, context.size()));
  unpack_others(context, all, bytes, count, row_bytes, order);
}

void gather_item_bytes(const Context& context, void* values, std::size_t count, std::size_t row_bytes,
                       const std::vector<std::uint32_t>* order) {
  auto* bytes = static_cast<unsigned char*>(values);
  const std::vector<unsigned char> packed = pack_mine(context, bytes, count, row_bytes, order);
  std::vector<unsigned char> all(context.is_root() ? count * row_bytes : 0);
  context.gather_rows(packed.data(), packed.size() / row_bytes, row_bytes, all.data(), row_counts(count, context.size()));
  if (context.is_root()) unpack_others(context, all, bytes, count, row_bytes, order);
}

}  // namespace prt::dist
