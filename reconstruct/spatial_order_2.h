// The spatial insertion order of 2D points, sorted on both cores.
#pragma once

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <utility>
#include <vector>

namespace scanstation {

/// Sorts (point, index) pairs into CGAL's randomized Hilbert order (BRIO,
/// `CGAL::spatial_sort` with the median policy), the halves of each split
/// sorted in parallel (TBB). The order is deterministic, but not the one
/// the sequential sort gives: CGAL's parallel sort restarts the curve's
/// orientation in each part of at most 8192 points.
void parallel_spatial_sort(std::vector<std::pair<CGAL::Epick::Point_2, int>>& points);

}  // namespace scanstation
