#include "core/far_points.h"

#include "core/unit_scale.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace scanstation {

namespace {

// Whether some other point of V lies within `reach` of V.row(v): the rows
// sorted by x, walked both ways from v's place while the x gap alone stays
// within reach (spiked vertices are few; the sort is shared).
bool has_point_within(const Eigen::MatrixXd& V, const std::vector<int>& by_x, const std::vector<int>& place, int v,
                      double reach) {
  const auto at = static_cast<std::ptrdiff_t>(place[static_cast<std::size_t>(v)]);
  const auto n = static_cast<std::ptrdiff_t>(by_x.size());
  for (const int step : {-1, 1})
    for (std::ptrdiff_t k = at + step; k >= 0 && k < n; k += step) {
      const int u = by_x[static_cast<std::size_t>(k)];
      if (std::abs(V(u, 0) - V(v, 0)) > reach) break;
      if ((V.row(u) - V.row(v)).norm() <= reach) return true;
    }
  return false;
}

}  // namespace

SpikedPoints spiked_points(const Eigen::MatrixXd& V, const Eigen::MatrixXi& cycles, double factor) {
  // Edge lengths near 1e±160 or beyond come out 0 or infinite: the same
  // points from the copy scaled by a power of two.
  if (const double s = unit_scale(V); beyond_squares(s)) return spiked_points(V * s, cycles, factor);
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
  const double reach = factor * *middle;
  if (!(reach > 0.0)) return {};
  SpikedPoints out;
  std::vector<int> by_x, place;
  for (std::size_t v = 0; v < shortest.size(); ++v) {
    if (!(shortest[v] < std::numeric_limits<double>::infinity() && shortest[v] > reach)) continue;
    if (by_x.empty()) {
      by_x.resize(static_cast<std::size_t>(V.rows()));
      std::iota(by_x.begin(), by_x.end(), 0);
      std::sort(by_x.begin(), by_x.end(), [&](int a, int b) { return V(a, 0) < V(b, 0); });
      place.resize(by_x.size());
      for (std::size_t i = 0; i < by_x.size(); ++i) place[static_cast<std::size_t>(by_x[i])] = static_cast<int>(i);
    }
    (has_point_within(V, by_x, place, static_cast<int>(v), reach) ? out.reached : out.far).push_back(static_cast<int>(v));
  }
  return out;
}

std::vector<int> far_points(const Eigen::MatrixXd& V, const Eigen::MatrixXi& cycles, double factor) {
  return spiked_points(V, cycles, factor).far;
}

}  // namespace scanstation
