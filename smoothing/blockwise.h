// Work over blocks of a range on all cores, with one partial result per
// block kept apart: combined in block order afterwards, the answer does not
// depend on the number of threads or on which thread ran which block
// (sums round the same way every run).
#pragma once

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstddef>
#include <vector>

namespace scanstation {

/// Calls f(begin, end, partial) for consecutive blocks [begin, end) of
/// [0, count), `block` indices each (the last may be shorter), in parallel;
/// returns the blocks' partials (value-initialised first) in block order.
template <typename Partial, typename F>
std::vector<Partial> blockwise(std::size_t count, std::size_t block, F&& f) {
  std::vector<Partial> partial((count + block - 1) / block);
  tbb::parallel_for(std::size_t{0}, partial.size(), [&](std::size_t b) {
    f(b * block, std::min(count, (b + 1) * block), partial[b]);
  });
  return partial;
}

}  // namespace scanstation
