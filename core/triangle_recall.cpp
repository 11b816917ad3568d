#include "core/triangle_recall.h"

#include <algorithm>
#include <array>
#include <vector>

namespace scanstation {

namespace {
std::vector<std::array<int, 3>> sorted_triples(const Eigen::MatrixX3i& F) {
  std::vector<std::array<int, 3>> t(static_cast<std::size_t>(F.rows()));
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    t[static_cast<std::size_t>(f)] = {F(f, 0), F(f, 1), F(f, 2)};
    std::sort(t[static_cast<std::size_t>(f)].begin(), t[static_cast<std::size_t>(f)].end());
  }
  std::sort(t.begin(), t.end());
  return t;
}
}  // namespace

double triangle_recall(const Eigen::MatrixX3i& truth, const Eigen::MatrixX3i& result) {
  if (truth.rows() == 0) return 0.0;
  const auto a = sorted_triples(truth), b = sorted_triples(result);
  std::size_t hits = 0;
  for (const auto& t : a) hits += std::binary_search(b.begin(), b.end(), t);
  return static_cast<double>(hits) / static_cast<double>(a.size());
}

}  // namespace scanstation
