// Passes over a complex's cells that need no order, by blocks on all cores.
#pragma once

#include <tbb/parallel_for.h>

#include <cstddef>
#include <numeric>
#include <vector>

namespace scanstation {

/// Cells per block: the copy of the triangulation, the boundary faces and the
/// kept cells are made block by block, each block's output at its own offset,
/// so the result is that of one pass in cell order.
inline constexpr std::size_t kCellBlock = std::size_t{1} << 15;

/// Calls body(b) for every b in [0, blocks): on all cores (TBB) when there
/// are two blocks or more, else inline (the incremental repair's local
/// complexes are one block each, many times per batch).
template <typename Body>
void for_each_block(std::size_t blocks, Body&& body) {
  if (blocks < 2) {
    for (std::size_t b = 0; b < blocks; ++b) body(b);
    return;
  }
  tbb::parallel_for(std::size_t{0}, blocks, body);
}

/// The first output row of each block, and the total at the end (blocks + 1
/// entries), from count(b), the rows block b writes (counted on all cores):
/// block b then writes its rows from offset[b], so the rows come in block
/// order, as from one pass.
template <typename Count>
std::vector<std::size_t> block_offsets(std::size_t blocks, Count&& count) {
  std::vector<std::size_t> offset(blocks + 1, 0);
  for_each_block(blocks, [&](std::size_t b) { offset[b + 1] = count(b); });
  std::partial_sum(offset.begin(), offset.end(), offset.begin());
  return offset;
}

}  // namespace scanstation
