#include "reconstruct/boundary_flips.h"

#include "reconstruct/boundary_surface.h"

#include <algorithm>
#include <deque>
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

}  // namespace

std::size_t flip_boundary(const Eigen::MatrixX3d& points, Eigen::MatrixX3i& boundary, FlipCriterion criterion,
                          const Eigen::MatrixXi& keep) {
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

  std::deque<std::pair<int, int>> edges;
  for (Eigen::Index f = 0; f < boundary.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (boundary(f, k) < boundary(f, (k + 1) % 3)) edges.emplace_back(boundary(f, k), boundary(f, (k + 1) % 3));
  std::size_t flips = 0;
  while (!edges.empty()) {
    const auto [a, b] = edges.front();
    edges.pop_front();
    const auto [f1, c] = face_with(surface, a, b);
    const auto [f2, d] = face_with(surface, b, a);
    if (f1 < 0 || f2 < 0 || c == d || surface.has_edge(c, d) || is_fixed(f1) || is_fixed(f2)) continue;
    const Triangle g1{a, d, c}, g2{d, b, c};
    const bool by_area = criterion == FlipCriterion::area;
    const double before = by_area ? area(surface, surface.face(f1)) + area(surface, surface.face(f2))
                                  : (surface.point(a) - surface.point(b)).squaredNorm();
    const double after = by_area ? area(surface, g1) + area(surface, g2) : (surface.point(c) - surface.point(d)).squaredNorm();
    if (!(after < before * (1.0 - 1e-9))) continue;
    if (CGAL::orientation(surface.exact(a), surface.exact(b), surface.exact(c), surface.exact(d)) == CGAL::COPLANAR)
      continue;
    if (surface.point_in_tetrahedron(a, b, c, d) || surface.meets_surface({g1, g2}, {f1, f2})) continue;
    surface.remove_face(f1);
    surface.remove_face(f2);
    surface.add_face(g1);
    surface.add_face(g2);
    ++flips;
    for (const auto& [u, v] : {std::pair{a, d}, std::pair{d, b}, std::pair{b, c}, std::pair{c, a}})
      edges.emplace_back(std::min(u, v), std::max(u, v));
  }
  boundary = surface.boundary();
  return flips;
}

}  // namespace scanstation
