// The orders in which a scan delivers its points, for feeding a known point
// set to the incremental reconstruction as a station would.
#pragma once

#include "sim/random.h"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numeric>
#include <vector>

namespace scanstation::sim {

/// P #P by 3. Row indices by angle about the vertical (z) axis through the
/// centroid, as a turntable scan delivers them (ties keep their order).
inline std::vector<Eigen::Index> turntable_order(const Eigen::MatrixX3d& P) {
  std::vector<Eigen::Index> order(static_cast<std::size_t>(P.rows()));
  std::iota(order.begin(), order.end(), Eigen::Index{0});
  const Eigen::RowVector3d c = P.colwise().mean();
  std::vector<double> angle(order.size());
  for (Eigen::Index i = 0; i < P.rows(); ++i) angle[static_cast<std::size_t>(i)] = std::atan2(P(i, 1) - c.y(), P(i, 0) - c.x());
  std::stable_sort(order.begin(), order.end(), [&](Eigen::Index a, Eigen::Index b) {
    return angle[static_cast<std::size_t>(a)] < angle[static_cast<std::size_t>(b)];
  });
  return order;
}

/// 0 .. n−1 shuffled (Fisher–Yates with a seeded Random: the same on every machine).
inline std::vector<Eigen::Index> shuffled_order(Eigen::Index n, std::uint64_t seed) {
  std::vector<Eigen::Index> order(static_cast<std::size_t>(n));
  std::iota(order.begin(), order.end(), Eigen::Index{0});
  Random random(seed);
  for (std::size_t i = order.size(); i > 1; --i) std::swap(order[i - 1], order[random.below(i)]);
  return order;
}

/// Rows [from, to) of the order, as a batch.
inline Eigen::MatrixX3d ordered_rows(const Eigen::MatrixX3d& P, const std::vector<Eigen::Index>& order, std::size_t from,
                                     std::size_t to) {
  Eigen::MatrixX3d out(static_cast<Eigen::Index>(to - from), 3);
  for (std::size_t k = from; k < to; ++k) out.row(static_cast<Eigen::Index>(k - from)) = P.row(order[k]);
  return out;
}

}  // namespace scanstation::sim
