#pragma once
// The one place prt talks to MPI (docs/distributed.md). A Context is the set of ranks of a job: rank()
// of size(). Built without MPI (PRT_WITH_MPI off), or run without mpirun, the world is this process
// alone (size 1) and every collective below is a copy or a no-op, so a single-process run does exactly
// what it did before this module existed.
//
// RULES. Collectives must be called by every rank, in the same order, from the thread that called
// world() first (MPI_THREAD_FUNNELED): the parallel_for workers never call MPI. A rank that fails on
// its own (bad input only it sees, out of memory) must end the whole job with abort_job(); a failure
// that every rank detects together (CollectiveError) lets every rank exit normally.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/error.h"

namespace prt::dist {

/// Bytes moved and seconds spent by the collectives of this process (for summaries and the scaling
/// model of docs/distributed.md). `wait_seconds` is time in the barrier before each exchange (other
/// ranks still computing), `exchange_seconds` the transfer after it.
struct ExchangeStats {
  std::uint64_t exchanges = 0;
  std::uint64_t bytes_sent = 0;      ///< this rank's payload, counted once per exchange
  std::uint64_t bytes_received = 0;  ///< the other ranks' payload this rank received
  double wait_seconds = 0.0;
  double exchange_seconds = 0.0;
};

/// An error that every rank raised at the same collective step with the same message: the CLI prints
/// it and exits with status 1 on every rank instead of aborting the job.
class CollectiveError : public Error {
 public:
  using Error::Error;
};

class Context {
 public:
  /// The job this process belongs to. First call: if the process was started by mpirun (Open MPI's
  /// OMPI_COMM_WORLD_SIZE or PMIx's PMIX_RANK in the environment) and prt was built with MPI, calls
  /// MPI_Init_thread (FUNNELED); otherwise the world is this process alone.
  static Context& world();
  /// A context of this process alone, without MPI (for libraries called with no context).
  static const Context& single();

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool is_root() const { return rank_ == 0; }
  /// True when MPI was initialised (even for mpirun -np 1).
  bool uses_mpi() const { return mpi_; }

  /// Every rank passes its `count` rows of `row_bytes` bytes; afterwards `all` holds every rank's
  /// rows, rank 0's first (counts[r] rows of rank r; counts.size() == size(), counts[rank()] == count).
  /// `all` may not overlap `mine`. Row-typed, so the count limit is 2^31 - 1 rows per rank.
  void allgather_rows(const void* mine, std::size_t count, std::size_t row_bytes, void* all,
                      const std::vector<std::size_t>& counts) const;
  /// The same, but only rank 0 receives (`all` is ignored elsewhere).
  void gather_rows(const void* mine, std::size_t count, std::size_t row_bytes, void* all,
                   const std::vector<std::size_t>& counts) const;
  /// Every rank's `values` (the same length on every rank), concatenated in rank order.
  std::vector<std::uint64_t> allgather_u64(const std::vector<std::uint64_t>& values) const;
  /// Sum over ranks.
  std::uint64_t sum(std::uint64_t value) const;
  /// Blocks until every rank arrives.
  void barrier() const;

  const ExchangeStats& stats() const { return stats_; }

  /// Ends MPI if it was started (idempotent; after it no collective may be called).
  void finalize();
  /// Ends the whole job from this rank: MPI_Abort(status) on a world of more than one rank (the
  /// launcher then kills every other rank), else std::exit(status). Never returns.
  [[noreturn]] void abort_job(int status);

 private:
  Context() = default;
  void init_from_environment();

  int rank_ = 0;
  int size_ = 1;
  bool mpi_ = false;
  bool finalized_ = false;
  mutable ExchangeStats stats_;
};

/// `context` if given, else Context::single(): what libraries use when their options carry no context.
inline const Context& or_single(const Context* context) { return context ? *context : Context::single(); }

/// The CLI's end of a command: finalizes MPI and returns `status`.
int finish(int status);
/// The CLI's end of a failed command, after printing its one-line message: a CollectiveError (or any
/// error in a single-rank world) finalizes and returns `status`; any other error on a rank of a larger
/// world aborts the job (abort_job) so that no rank waits forever in a collective.
int finish_after_error(int status, bool collective);

}  // namespace prt::dist
