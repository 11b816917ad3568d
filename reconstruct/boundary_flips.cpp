#include "reconstruct/boundary_flips.h"

#include "reconstruct/boundary_surface.h"

#include <algorithm>
#include <queue>
#include <tuple>
#include <utility>

namespace scanstation {

namespace {

using Triangle = BoundarySurface::Triangle;

double area(const BoundarySurface& s, const Triangle& t) {
  return 0.5 * (s.point(t[1]) - s.point(t[0])).cross(s.point(t[2]) - s.point(t[0])).norm();
}

// The face holding the directed edge a → b, and its third vertex.
std::pair<int, int> face_with(const BoundarySurface& s, int a, int b) {
  for (const int f : s.faces_at(a)) {
    const Triangle& t = s.face(f);
    for (int k = 0; k < 3; ++k)
      if (t[static_cast<std::size_t>(k)] == a && t[static_cast<std::size_t>((k + 1) % 3)] == b)
        return {f, t[static_cast<std::size_t>((k + 2) % 3)]};
  }
  return {-1, -1};
}

// Edges (a < b) whose flip would lower the area enough, found from the face
// list alone, so that a surface with none costs two linear passes and no
// spatial index. The half-edges are bucketed by their lower vertex (counting
// sort: a million-face surface has six million half-edges, too many for a
// comparison sort to be cheap), then paired within each small bucket.
std::vector<std::pair<int, int>> candidate_edges(const Eigen::MatrixX3d& P, const Eigen::MatrixX3i& F, double min_gain) {
  struct Half {
    int hi, opposite;
    bool forward;
    double area;
  };
  std::vector<std::size_t> start(static_cast<std::size_t>(P.rows()) + 1, 0);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) ++start[static_cast<std::size_t>(std::min(F(f, k), F(f, (k + 1) % 3))) + 1];
  for (std::size_t v = 1; v < start.size(); ++v) start[v] += start[v - 1];
  std::vector<Half> halves(start.back());
  std::vector<std::size_t> fill(start.begin(), start.end() - 1);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d p0 = P.row(F(f, 0)), p1 = P.row(F(f, 1)), p2 = P.row(F(f, 2));
    const double a = 0.5 * (p1 - p0).cross(p2 - p0).norm();
    for (int k = 0; k < 3; ++k) {
      const int u = F(f, k), v = F(f, (k + 1) % 3);
      halves[fill[static_cast<std::size_t>(std::min(u, v))]++] = {std::max(u, v), F(f, (k + 2) % 3), u < v, a};
    }
  }
  std::vector<std::pair<int, int>> out;
  for (std::size_t lo = 0; lo + 1 < start.size(); ++lo) {
    const auto first = halves.begin() + static_cast<std::ptrdiff_t>(start[lo]);
    const auto last = halves.begin() + static_cast<std::ptrdiff_t>(start[lo + 1]);
    std::sort(first, last, [](const Half& x, const Half& y) { return std::tie(x.hi, x.forward) < std::tie(y.hi, y.forward); });
    for (auto x = first; x != last && x + 1 != last; ++x) {
      const auto y = x + 1;
      if (x->hi != y->hi) continue;
      const Eigen::Vector3d a = P.row(static_cast<Eigen::Index>(lo)), b = P.row(x->hi), c = P.row(x->opposite),
                            d = P.row(y->opposite);
      // The two new triangles {a, c, d} and {b, c, d}, whichever face c is on.
      const double after = 0.5 * ((d - a).cross(c - a).norm() + (b - d).cross(c - d).norm());
      if (after < (x->area + y->area) * (1.0 - min_gain)) out.emplace_back(static_cast<int>(lo), x->hi);
    }
  }
  return out;
}

}  // namespace

std::size_t flip_boundary(const Eigen::MatrixX3d& points, Eigen::MatrixX3i& boundary, FlipCriterion criterion,
                          const Eigen::MatrixXi& keep, double min_gain) {
  (void)criterion;
  std::vector<std::pair<int, int>> first = candidate_edges(points, boundary, min_gain);
  if (first.empty()) return 0;
  BoundarySurface surface(points, boundary);
  std::vector<Triangle> fixed;
  for (Eigen::Index k = 0; k < keep.rows(); ++k) {
    Triangle t{keep(k, 0), keep(k, 1), keep(k, 2)};
    std::sort(t.begin(), t.end());
    fixed.push_back(t);
  }
  std::sort(fixed.begin(), fixed.end());
  const auto is_fixed = [&](int f) {
    Triangle t = surface.face(f);
    std::sort(t.begin(), t.end());
    return std::binary_search(fixed.begin(), fixed.end(), t);
  };

  // Largest relative area drop first: caps over concavities go before the
  // small corrections around them.
  struct Candidate {
    double gain;
    int a, b;
    bool operator<(const Candidate& o) const { return gain != o.gain ? gain < o.gain : std::tie(a, b) > std::tie(o.a, o.b); }
  };
  std::priority_queue<Candidate> edges;
  const auto gain_of = [&](int a, int b) {
    const auto [f1, c] = face_with(surface, a, b);
    const auto [f2, d] = face_with(surface, b, a);
    if (f1 < 0 || f2 < 0 || c == d) return 0.0;
    const double before = area(surface, surface.face(f1)) + area(surface, surface.face(f2));
    const double after = area(surface, {a, d, c}) + area(surface, {d, b, c});
    return before > 0 ? 1.0 - after / before : 0.0;
  };
  for (const auto& [a, b] : first) edges.push({gain_of(a, b), a, b});
  std::size_t flips = 0;
  while (!edges.empty()) {
    const Candidate top = edges.top();
    edges.pop();
    const int a = top.a, b = top.b;
    const auto [f1, c] = face_with(surface, a, b);
    const auto [f2, d] = face_with(surface, b, a);
    if (f1 < 0 || f2 < 0 || c == d || surface.has_edge(c, d) || is_fixed(f1) || is_fixed(f2)) continue;
    const Triangle g1{a, d, c}, g2{d, b, c};
    // FlipCriterion::area, the only criterion so far.
    const double before = area(surface, surface.face(f1)) + area(surface, surface.face(f2));
    const double after = area(surface, g1) + area(surface, g2);
    if (!(after < before * (1.0 - min_gain))) continue;
    if (CGAL::orientation(surface.exact(a), surface.exact(b), surface.exact(c), surface.exact(d)) == CGAL::COPLANAR)
      continue;
    if (surface.point_in_tetrahedron(a, b, c, d) || surface.meets_surface({g1, g2}, {f1, f2})) continue;
    surface.remove_face(f1);
    surface.remove_face(f2);
    surface.add_face(g1);
    surface.add_face(g2);
    ++flips;
    for (const auto& [u, v] : {std::pair{a, d}, std::pair{d, b}, std::pair{b, c}, std::pair{c, a}}) {
      const double g = gain_of(std::min(u, v), std::max(u, v));
      if (g > min_gain) edges.push({g, std::min(u, v), std::max(u, v)});
    }
  }
  boundary = surface.boundary();
  return flips;
}

}  // namespace scanstation
