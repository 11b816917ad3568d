// Brute-force γ-graphs written straight from Definitions 3.1–3.3, for tests
// only. Nothing here uses the pencil interval (lo, hi) of the fast code:
//  - N_γ(c0,c1) is built as two explicit balls (centre, radius) or
//    half-spaces placed as Definition 3.1 says, and every other vertex is
//    tested for membership in the union / intersection / open simplex;
//  - Definition 3.3's largest (c'0, c'1) is found by trying the finitely many
//    parameter values where emptiness can change (the balls through the
//    simplex and one more vertex, as in the proof of Theorem 3.1, plus -1,0,1),
//    c1 from the largest down, then c0 from the largest down, each tried with
//    the membership test above. That is the reading c'1 = largest c1 with an
//    empty N_γ(·,c1), c'0 = largest c0 with N_γ(c0,c'1) empty.
// Finite balls are tested in doubles with a relative tolerance of 1e-9 so a
// vertex on the sphere that defines the candidate value counts as outside
// (open ball); half-spaces and the open simplex use exact orientation.
// Cost O(N^{k+1}) for γ(c0,c1), O(N^{k+3}) for Definition 3.3: keep N small.
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <vector>

#include "core/predicates.h"

namespace scanstation::test {

template <int D>
struct BruteSimplex {
  using Vec = Eigen::Matrix<double, D, 1>;
  std::array<Vec, D> v;
  Vec m, n;  // circumcentre of the simplex in its hyperplane, unit normal
  double r = 0;

  // +1 / -1 side of the hyperplane (exact), 0 on it.
  int side(const Vec& p) const {
    if constexpr (D == 2) {
      return orientation(v[0], v[1], p);
    } else {
      return orientation(v[0], v[1], v[2], p);
    }
  }
  // p in the open simplex (interior of R, Definition 3.1).
  bool in_open_simplex(const Vec& p) const {
    if (side(p) != 0) return false;
    if constexpr (D == 2) {
      return (p - v[0]).dot(v[1] - v[0]) > 0 && (p - v[1]).dot(v[0] - v[1]) > 0;
    } else {
      for (int i = 0; i < 3; ++i) {
        const Vec a = v[i], b = v[(i + 1) % 3], c = v[(i + 2) % 3];
        if ((b - a).cross(p - a).dot((b - a).cross(c - a)) <= 0) return false;
      }
      return true;
    }
  }
};

template <int D>
std::optional<BruteSimplex<D>> brute_simplex(const std::array<typename BruteSimplex<D>::Vec, D>& v) {
  BruteSimplex<D> s;
  s.v = v;
  if constexpr (D == 2) {
    s.m = 0.5 * (v[0] + v[1]);
    s.r = 0.5 * (v[1] - v[0]).norm();
    s.n = Eigen::Vector2d(-(v[1] - v[0]).y(), (v[1] - v[0]).x()).normalized();
  } else {
    const Eigen::Vector3d u = v[1] - v[0], w = v[2] - v[0], nn = u.cross(w);
    if (nn.squaredNorm() == 0) return std::nullopt;  // collinear: no simplex
    // Circumcentre: m = v0 + x u + y w with (m - v0)·u = |u|²/2, (m - v0)·w = |w|²/2.
    Eigen::Matrix2d A;
    A << u.dot(u), u.dot(w), u.dot(w), w.dot(w);
    const Eigen::Vector2d xy = A.lu().solve(Eigen::Vector2d(u.dot(u) / 2, w.dot(w) / 2));
    s.m = v[0] + xy[0] * u + xy[1] * w;
    s.r = (s.m - v[0]).norm();
    s.n = nn.normalized();
  }
  return s;
}

// A ball touching the simplex with parameter c on side `side` (Definition 3.1:
// radius r/(1-|c|)); |c| = 1 is the open half-space on that side.
template <int D>
struct BruteBall {
  const BruteSimplex<D>* s;
  double c;
  int side;
  bool contains(const typename BruteSimplex<D>::Vec& p) const {
    if (std::abs(c) >= 1) return s->side(p) == side;
    const double R = s->r / (1 - std::abs(c));
    const double off = std::sqrt(std::max(0.0, R * R - s->r * s->r));
    const auto centre = s->m + side * off * s->n;
    return (p - centre).squaredNorm() < R * R * (1 - 1e-9);
  }
};

// Is one of the two N_γ(c0,c1) of simplex s empty of the vertices `others`?
template <int D>
bool brute_empty(const BruteSimplex<D>& s, const std::vector<typename BruteSimplex<D>::Vec>& others, double c0,
                 double c1) {
  for (int sigma : {1, -1}) {
    const BruteBall<D> B1{&s, c1, sigma};
    const BruteBall<D> B0{&s, c0, c0 * c1 < 0 ? sigma : -sigma};  // same side iff c0c1 < 0
    bool empty = true;
    for (const auto& p : others) {
      const bool inside = s.in_open_simplex(p) ||
                          (c1 >= 0 ? (B0.contains(p) || B1.contains(p)) : (B0.contains(p) && B1.contains(p)));
      if (inside) {
        empty = false;
        break;
      }
    }
    if (empty) return true;
  }
  return false;
}

template <int D>
using BruteRow = std::array<int, D>;

template <int D>
std::vector<BruteRow<D>> all_subsets(int n) {
  std::vector<BruteRow<D>> out;
  BruteRow<D> s{};
  const auto rec = [&](auto&& self, int from, int depth) -> void {
    if (depth == D) return out.push_back(s);
    for (int i = from; i < n; ++i) s[depth] = i, self(self, i + 1, depth + 1);
  };
  rec(rec, 0, 0);
  return out;
}

template <int D>
struct BruteCase {
  std::optional<BruteSimplex<D>> simplex;
  std::vector<typename BruteSimplex<D>::Vec> others;
};

template <int D>
BruteCase<D> brute_case(const Eigen::Matrix<double, Eigen::Dynamic, D>& V, const BruteRow<D>& row) {
  std::array<typename BruteSimplex<D>::Vec, D> v;
  for (int i = 0; i < D; ++i) v[i] = V.row(row[i]).transpose();
  BruteCase<D> bc{brute_simplex<D>(v), {}};
  for (int i = 0; i < V.rows(); ++i)
    if (std::find(row.begin(), row.end(), i) == row.end()) bc.others.push_back(V.row(i).transpose());
  return bc;
}

/// γ(c0,c1) by Definition 3.2: rows i < j (< k), sorted.
template <int D>
std::vector<BruteRow<D>> brute_gamma(const Eigen::Matrix<double, Eigen::Dynamic, D>& V, double c0, double c1) {
  std::vector<BruteRow<D>> out;
  for (const auto& row : all_subsets<D>(static_cast<int>(V.rows()))) {
    const auto bc = brute_case<D>(V, row);
    if (bc.simplex && brute_empty<D>(*bc.simplex, bc.others, c0, c1)) out.push_back(row);
  }
  return out;
}

/// Definition 3.3's (c'0, c'1) of one simplex, or nullopt when no N_γ is empty.
template <int D>
std::optional<Eigen::Vector2d> brute_largest(const BruteCase<D>& bc) {
  if (!bc.simplex) return std::nullopt;
  const auto& s = *bc.simplex;
  std::vector<double> values{-1, 0, 1};
  for (const auto& p : bc.others) {
    // Circumradius of the simplex plus p: centre x with |x - v_i| = |x - p|.
    Eigen::Matrix<double, D, D> A;
    Eigen::Matrix<double, D, 1> b;
    const auto& v0 = s.v[0];
    for (int i = 1; i < D; ++i) A.row(i - 1) = 2 * (s.v[i] - v0).transpose(), b[i - 1] = s.v[i].squaredNorm() - v0.squaredNorm();
    A.row(D - 1) = 2 * (p - v0).transpose(), b[D - 1] = p.squaredNorm() - v0.squaredNorm();
    if (std::abs(A.determinant()) < 1e-300) continue;  // p in the hyperplane: only half-spaces
    const double R = (A.fullPivLu().solve(b) - v0).norm();
    const double c = 1 - s.r / R;
    values.push_back(c);
    values.push_back(-c);
  }
  std::sort(values.begin(), values.end());
  values.erase(std::unique(values.begin(), values.end()), values.end());
  for (auto c1 = values.rbegin(); c1 != values.rend(); ++c1) {
    std::vector<double> c0s{std::abs(*c1), -std::abs(*c1)};
    for (double v : values)
      if (std::abs(v) <= std::abs(*c1)) c0s.push_back(v);
    std::sort(c0s.rbegin(), c0s.rend());
    for (double c0 : c0s)
      if (brute_empty<D>(s, bc.others, c0, *c1)) return Eigen::Vector2d(c0, *c1);
  }
  return std::nullopt;
}

/// γ([c0,c1],[c2,c3]) by Definition 3.3.
template <int D>
std::vector<BruteRow<D>> brute_gamma_range(const Eigen::Matrix<double, Eigen::Dynamic, D>& V, double c0, double c1,
                                           double c2, double c3) {
  std::vector<BruteRow<D>> out;
  for (const auto& row : all_subsets<D>(static_cast<int>(V.rows()))) {
    const auto c = brute_largest<D>(brute_case<D>(V, row));
    if (c && (*c)[0] >= c0 && (*c)[0] <= c1 && (*c)[1] >= c2 && (*c)[1] <= c3) out.push_back(row);
  }
  return out;
}

}  // namespace scanstation::test
