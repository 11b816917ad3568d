#include "core/unique_points.h"

#include <algorithm>
#include <array>

namespace scanstation {

Eigen::Index unique_points(const Eigen::MatrixX3d& P, std::vector<Eigen::Index>& first, std::vector<Eigen::Index>& map) {
  const Eigen::Index n = P.rows();
  // Sorting contiguous (point, row) records is several times faster than
  // sorting row indices through the matrix; the row as last key makes the
  // first occurrence lead each run of equal points. Adding 0.0 turns −0.0
  // into +0.0, so the comparison is by value.
  struct Record {
    std::array<double, 3> key;
    Eigen::Index row;
    bool operator<(const Record& o) const { return key != o.key ? key < o.key : row < o.row; }
  };
  std::vector<Record> records(static_cast<std::size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i) records[static_cast<std::size_t>(i)] = {{P(i, 0) + 0.0, P(i, 1) + 0.0, P(i, 2) + 0.0}, i};
  std::sort(records.begin(), records.end());

  std::vector<Eigen::Index> representative(static_cast<std::size_t>(n));
  Eigen::Index lead = 0;
  for (std::size_t k = 0; k < records.size(); ++k) {
    if (k == 0 || records[k].key != records[k - 1].key) lead = records[k].row;
    representative[static_cast<std::size_t>(records[k].row)] = lead;
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
