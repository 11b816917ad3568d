// The spatial insertion order of points: BRIO rounds, each along a Hilbert
// curve, sorted by integer keys on all cores.
#pragma once

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <cstdint>
#include <utility>
#include <vector>

namespace scanstation {

/// Index of the cell (x, y) of a 2^28 × 2^28 grid along the Hilbert curve
/// that starts at (0, 0) and ends at (2^28 − 1, 0); x, y < 2^28.
std::uint64_t hilbert_index_2(std::uint32_t x, std::uint32_t y);

/// Index of the cell (x, y, z) of a 2^19-cell cube along a 3D Hilbert curve
/// starting at (0, 0, 0) (Skilling's construction, "Programming the Hilbert
/// curve", 2004); x, y, z < 2^19.
std::uint64_t hilbert_index_3(std::uint32_t x, std::uint32_t y, std::uint32_t z);

/// Index of the cell (x, y, z) along the Morton (Z-order) curve: the bits
/// of x, y, z interleaved; x, y, z < 2^21. Cheaper than hilbert_index_3 and
/// nearly as local: for orders that only need nearby items together.
std::uint64_t morton_index_3(std::uint32_t x, std::uint32_t y, std::uint32_t z);

/// Sorts (point, index) pairs into a biased randomized insertion order
/// (BRIO, Amenta, Choi & Rote 2003) as `CGAL::spatial_sort` makes it: the
/// last round holds three quarters of the points, each earlier round a
/// quarter of the round after it, down to 16 points, and each round follows
/// a Hilbert curve. The curve is that of a square (cubic) grid over the
/// points' bounding box, 2^28 (3D: 2^19) cells a side; more than 32 points
/// of one round in one cell (a far outlier squeezes the rest into a few
/// cells) are ordered again on a grid over their own box, up to 4 times,
/// and equal points keep their order. The rounds are drawn by a hash of
/// the position in `points`, so the order is deterministic and the same on
/// any number of threads.
///
/// CGAL's median policy cuts at medians instead of grid lines: the keys
/// here are computed and sorted on all cores in a few passes, where the
/// median sort is a recursion of selections.
void brio_hilbert_sort(std::vector<std::pair<CGAL::Epick::Point_2, int>>& points);
void brio_hilbert_sort(std::vector<std::pair<CGAL::Epick::Point_3, int>>& points);

}  // namespace scanstation
