// Context without MPI (PRT_WITH_MPI off): a world of one rank; collectives copy or do nothing.
#include <cstdlib>
#include <cstring>

#include "dist/context.h"

namespace prt::dist {

void Context::init_from_environment() {}

void Context::allgather_rows(const void* mine, std::size_t count, std::size_t row_bytes, void* all,
                             const std::vector<std::size_t>&) const {
  if (count > 0) std::memmove(all, mine, count * row_bytes);
}

void Context::gather_rows(const void* mine, std::size_t count, std::size_t row_bytes, void* all,
                          const std::vector<std::size_t>& counts) const {
  allgather_rows(mine, count, row_bytes, all, counts);
}

std::vector<std::uint64_t> Context::allgather_u64(const std::vector<std::uint64_t>& values) const { return values; }
std::uint64_t Context::sum(std::uint64_t value) const { return value; }
void Context::barrier() const {}
void Context::finalize() { finalized_ = true; }
void Context::abort_job(int status) { std::exit(status); }

}  // namespace prt::dist
