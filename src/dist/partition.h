#pragma once
// How a job's items (vertices, probes, pixels) are split over the ranks of a distributed run
// (docs/distributed.md). Items are visited in a given order (the Morton order of the bake and the
// reference, the file order of the probes); rank r of P owns the contiguous run of positions
//     [floor(N r / P), floor(N (r + 1) / P))
// of that order, so each rank works on a spatially coherent region and the split depends only on N and
// P. Which rank computes an item never changes its result (every item's result depends only on the
// inputs, the options and its index), so the gathered output is the same for any P.
#include <cstddef>
#include <vector>

namespace prt::dist {

/// A run [begin, end) of positions in the visiting order.
struct Range {
  std::size_t begin = 0;
  std::size_t end = 0;
  std::size_t size() const { return end - begin; }
};

/// The positions of `count` items owned by rank `rank` of `ranks` (0 <= rank < ranks, ranks >= 1).
Range partition(std::size_t count, int ranks, int rank);

/// partition(count, ranks, r) for every rank r, in rank order (their runs tile [0, count)).
std::vector<Range> partitions(std::size_t count, int ranks);

}  // namespace prt::dist
