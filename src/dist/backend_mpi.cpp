// Context on MPI (PRT_WITH_MPI on): MPI_COMM_WORLD, initialised FUNNELED when launched by mpirun.
// The only file of prt that includes mpi.h; only its C API is used, so the deprecated C++ bindings
// are kept out.
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <chrono>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include <mpi.h>

#include "core/stopwatch.h"
#include "dist/context.h"

namespace prt::dist {

namespace {

bool launched_by_mpirun() {
  return std::getenv("OMPI_COMM_WORLD_SIZE") != nullptr || std::getenv("PMIX_RANK") != nullptr ||
         std::getenv("PMI_SIZE") != nullptr;
}

int to_int(std::size_t value, const char* what) {
  if (value > static_cast<std::size_t>(INT_MAX)) fail(std::string("dist: ") + what + " too large for one MPI exchange");
  return static_cast<int>(value);
}

// A contiguous MPI datatype of one row, freed on scope exit.
class RowType {
 public:
  explicit RowType(std::size_t row_bytes) {
    MPI_Type_contiguous(to_int(row_bytes, "row"), MPI_BYTE, &type_);
    MPI_Type_commit(&type_);
  }
  ~RowType() { MPI_Type_free(&type_); }
  RowType(const RowType&) = delete;
  RowType& operator=(const RowType&) = delete;
  MPI_Datatype get() const { return type_; }

 private:
  MPI_Datatype type_;
};

struct Layout {
  std::vector<int> counts, displacements;
  std::size_t total = 0;
};

Layout layout_of(const std::vector<std::size_t>& counts) {
  Layout l;
  for (std::size_t c : counts) {
    l.counts.push_back(to_int(c, "row count"));
    l.displacements.push_back(to_int(l.total, "row offset"));
    l.total += c;
  }
  return l;
}

}  // namespace

void Context::init_from_environment() {
  if (!launched_by_mpirun()) return;
  int provided = 0;
  if (MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS) fail("dist: MPI_Init_thread failed");
  if (provided < MPI_THREAD_FUNNELED) fail("dist: the MPI library does not support MPI_THREAD_FUNNELED");
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  mpi_ = true;
}

namespace {

// The rows exchange of allgather_rows (to_root false) and gather_rows (to_root true): a timed barrier
// (the wait for the slowest rank), then the timed collective.
void exchange_rows(const void* mine, std::size_t count, std::size_t row_bytes, void* all, const std::vector<std::size_t>& counts,
                   bool to_root, int size, int rank, ExchangeStats& stats) {
  if (size == 1) {  // a world of one rank (mpirun -np 1): a copy
    if (count > 0) std::memmove(all, mine, count * row_bytes);
    return;
  }
  const Layout l = layout_of(counts);
  const RowType row(row_bytes);
  auto start = std::chrono::steady_clock::now();
  MPI_Barrier(MPI_COMM_WORLD);
  stats.wait_seconds += seconds_since(start);
  start = std::chrono::steady_clock::now();
  const int n = to_int(count, "row count");
  if (to_root)
    MPI_Gatherv(mine, n, row.get(), all, l.counts.data(), l.displacements.data(), row.get(), 0, MPI_COMM_WORLD);
  else
    MPI_Allgatherv(mine, n, row.get(), all, l.counts.data(), l.displacements.data(), row.get(), MPI_COMM_WORLD);
  stats.exchange_seconds += seconds_since(start);
  stats.exchanges += 1;
  stats.bytes_sent += count * row_bytes;
  if (!to_root || rank == 0) stats.bytes_received += (l.total - count) * row_bytes;
}

}  // namespace

void Context::allgather_rows(const void* mine, std::size_t count, std::size_t row_bytes, void* all,
                             const std::vector<std::size_t>& counts) const {
  exchange_rows(mine, count, row_bytes, all, counts, false, size_, rank_, stats_);
}

void Context::gather_rows(const void* mine, std::size_t count, std::size_t row_bytes, void* all,
                          const std::vector<std::size_t>& counts) const {
  exchange_rows(mine, count, row_bytes, all, counts, true, size_, rank_, stats_);
}

std::vector<std::uint64_t> Context::allgather_u64(const std::vector<std::uint64_t>& values) const {
  if (size_ == 1) return values;
  std::vector<std::uint64_t> all(values.size() * static_cast<std::size_t>(size_));
  const int n = to_int(values.size(), "value count");
  MPI_Allgather(values.data(), n, MPI_UINT64_T, all.data(), n, MPI_UINT64_T, MPI_COMM_WORLD);
  return all;
}

std::uint64_t Context::sum(std::uint64_t value) const {
  if (size_ == 1) return value;
  std::uint64_t total = 0;
  MPI_Allreduce(&value, &total, 1, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
  return total;
}

void Context::barrier() const {
  if (size_ > 1) MPI_Barrier(MPI_COMM_WORLD);
}

void Context::finalize() {
  if (mpi_ && !finalized_) MPI_Finalize();
  finalized_ = true;
}

void Context::abort_job(int status) {
  std::fflush(stderr);
  if (mpi_ && !finalized_ && size_ > 1) MPI_Abort(MPI_COMM_WORLD, status);
  finalize();
  std::exit(status);
}

}  // namespace prt::dist
