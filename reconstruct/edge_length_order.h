// Edges in order of exact length (the EMST's Kruskal order, chapter 2).
//
// A comparison sort with CGAL's filtered compare_distance falls to exact
// arithmetic whenever two lengths are within rounding of each other, and on
// a lattice whose spacing is no binary fraction (0.1) nearly every pair of
// edges is: a 300×300 grid took 8 s for its EMST, almost all of it in
// exact comparisons. Here each edge's squared length is computed once in
// doubles with a bound on its rounding; the edges are sorted by it, and
// only runs of edges whose bounds overlap are ordered again, by lengths
// that are exact: the doubles themselves when every step of their
// computation was error-free (a lattice of binary fractions), else
// CGAL::Exact_rational computed once per edge. The order is the one the
// exact comparison gives, ties broken by `before`.
#pragma once

#include <CGAL/Exact_rational.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace scanstation {

namespace edge_length_order_detail {

// fl(a − b) and whether it is exact (Knuth's two-sum error is zero).
inline std::pair<double, bool> difference(double a, double b) {
  const double s = a - b;
  const double bb = s - a;
  return {s, (a - (s - bb)) + (-b - bb) == 0.0};
}

// fl(x + y) and whether it is exact.
inline std::pair<double, bool> sum(double x, double y) {
  const double s = x + y;
  const double yy = s - x;
  return {s, (x - (s - yy)) + (y - yy) == 0.0};
}

}  // namespace edge_length_order_detail

/// Sorts `edges` (index pairs into P, CGAL Point_2 or Point_3 with double
/// coordinates) by exact length, equal lengths by `before` (a strict order
/// on edges).
template <typename Point, typename Edge, typename Before>
void sort_by_length(std::vector<Edge>& edges, const std::vector<Point>& P, Before before) {
  using namespace edge_length_order_detail;
  constexpr int D = Point::Ambient_dimension::value;
  struct Keyed {
    double key;  // squared length in doubles
    bool exact;  // key is the exact squared length
    Edge e;
  };
  std::vector<Keyed> keyed;
  keyed.reserve(edges.size());
  for (const Edge& e : edges) {
    const Point &p = P[static_cast<std::size_t>(e[0])], &q = P[static_cast<std::size_t>(e[1])];
    double key = 0.0;
    bool exact = true;
    for (int i = 0; i < D; ++i) {
      const auto [d, d_exact] = difference(p[i], q[i]);
      const double square = d * d;
      const auto [s, s_exact] = sum(key, square);
      // fma's residual is exact only for a product that is no subnormal.
      const bool square_exact = d == 0.0 || (square >= 0x1p-969 && std::fma(d, d, -square) == 0.0);
      exact = exact && d_exact && square_exact && s_exact;
      key = s;
    }
    keyed.push_back({key, exact && std::isfinite(key), e});
  }
  std::sort(keyed.begin(), keyed.end(), [&](const Keyed& a, const Keyed& b) {
    return a.key != b.key ? a.key < b.key : before(a.e, b.e);
  });
  // Each rounding is within a relative 2^-53, or an absolute DBL_MIN-sized
  // step below the normal range: 2D + 1 of them bound the key's error.
  constexpr double kRelative = 16 * std::numeric_limits<double>::epsilon();
  constexpr double kAbsolute = 64 * std::numeric_limits<double>::denorm_min() * (1ull << 53);
  const auto upper = [&](double key) { return key + kRelative * key + kAbsolute; };
  const auto lower = [&](double key) { return key - kRelative * key - kAbsolute; };
  std::vector<std::pair<CGAL::Exact_rational, Edge>> exact_run;
  for (std::size_t first = 0; first < keyed.size();) {
    std::size_t last = first + 1;  // the run: keys whose bounds chain together
    bool all_exact = keyed[first].exact;
    while (last < keyed.size() && !(lower(keyed[last].key) > upper(keyed[last - 1].key))) {
      all_exact = all_exact && keyed[last].exact;
      ++last;
    }
    if (last - first > 1 && !all_exact) {
      exact_run.clear();
      for (std::size_t k = first; k < last; ++k) {
        const Edge& e = keyed[k].e;
        const Point &p = P[static_cast<std::size_t>(e[0])], &q = P[static_cast<std::size_t>(e[1])];
        CGAL::Exact_rational length2 = 0;
        for (int i = 0; i < D; ++i) {
          const CGAL::Exact_rational d = CGAL::Exact_rational(p[i]) - CGAL::Exact_rational(q[i]);
          length2 += d * d;
        }
        exact_run.emplace_back(std::move(length2), e);
      }
      std::sort(exact_run.begin(), exact_run.end(), [&](const auto& a, const auto& b) {
        return a.first != b.first ? a.first < b.first : before(a.second, b.second);
      });
      for (std::size_t k = first; k < last; ++k) keyed[k].e = exact_run[k - first].second;
    }
    first = last;
  }
  for (std::size_t k = 0; k < keyed.size(); ++k) edges[k] = keyed[k].e;
}

}  // namespace scanstation
