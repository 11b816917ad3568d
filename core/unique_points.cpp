#include "core/unique_points.h"

#include <algorithm>
#include <array>
#include <numeric>

namespace scanstation {

Eigen::Index unique_points(const Eigen::MatrixX3d& P, std::vector<Eigen::Index>& first, std::vector<Eigen::Index>& map) {
  const Eigen::Index n = P.rows();
  // Adding 0.0 turns −0.0 into +0.0, so the comparison is by value.
  auto key = [&](Eigen::Index i) { return std::array<double, 3>{P(i, 0) + 0.0, P(i, 1) + 0.0, P(i, 2) + 0.0}; };
  std::vector<Eigen::Index> order(static_cast<std::size_t>(n));
  std::iota(order.begin(), order.end(), Eigen::Index{0});
  std::stable_sort(order.begin(), order.end(), [&](Eigen::Index a, Eigen::Index b) { return key(a) < key(b); });

  std::vector<Eigen::Index> representative(static_cast<std::size_t>(n));
  for (std::size_t k = 0; k < order.size(); ++k) {
    const bool repeat = k > 0 && key(order[k]) == key(order[k - 1]);
    representative[static_cast<std::size_t>(order[k])] = repeat ? representative[static_cast<std::size_t>(order[k - 1])] : order[k];
  }
  first.clear();
  map.assign(static_cast<std::size_t>(n), 0);
  std::vector<Eigen::Index> slot(static_cast<std::size_t>(n), -1);
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto r = static_cast<std::size_t>(representative[static_cast<std::size_t>(i)]);
    if (slot[r] < 0) {
      slot[r] = static_cast<Eigen::Index>(first.size());
      first.push_back(i);
    }
    map[static_cast<std::size_t>(i)] = slot[r];
  }
  return n - static_cast<Eigen::Index>(first.size());
}

}  // namespace scanstation
