#include "core/far_points.h"

#include <algorithm>
#include <limits>

namespace scanstation {

std::vector<int> far_points(const Eigen::MatrixXd& V, const Eigen::MatrixXi& cycles, double factor) {
  std::vector<double> shortest(static_cast<std::size_t>(V.rows()), std::numeric_limits<double>::infinity());
  const Eigen::Index k = cycles.cols();
  for (Eigen::Index f = 0; f < cycles.rows(); ++f)
    for (Eigen::Index i = 0; i < k; ++i) {
      const int a = cycles(f, i), b = cycles(f, (i + 1) % k);
      const double length = (V.row(a) - V.row(b)).norm();
      shortest[static_cast<std::size_t>(a)] = std::min(shortest[static_cast<std::size_t>(a)], length);
      shortest[static_cast<std::size_t>(b)] = std::min(shortest[static_cast<std::size_t>(b)], length);
    }
  std::vector<double> on_edges;
  for (const double s : shortest)
    if (s < std::numeric_limits<double>::infinity()) on_edges.push_back(s);
  if (on_edges.size() < 3) return {};
  const auto middle = on_edges.begin() + static_cast<std::ptrdiff_t>(on_edges.size() / 2);
  std::nth_element(on_edges.begin(), middle, on_edges.end());
  const double median = *middle;
  if (!(median > 0.0)) return {};
  std::vector<int> far;
  for (std::size_t v = 0; v < shortest.size(); ++v)
    if (shortest[v] < std::numeric_limits<double>::infinity() && shortest[v] > factor * median)
      far.push_back(static_cast<int>(v));
  return far;
}

}  // namespace scanstation
