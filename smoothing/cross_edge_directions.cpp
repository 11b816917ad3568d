#include "smoothing/cross_edge_directions.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace scanstation {

namespace {

constexpr double kPi = 3.14159265358979323846;

// One macro edge end: V, the edge's other end A, and the third corners B and
// C of the triangles (V, A, B) and (V, C, A).
struct End {
  int V, A, B, C;
};

// The sine of the angle between an end's two cross-edge directions under
// the normal n (0: they line up).
double separation(const Eigen::MatrixX3d& P, const End& e, const Eigen::Vector3d& n, CrossEdgePoints points) {
  const Eigen::Vector3d v = P.row(e.V);
  const auto projected = [&](int x) -> Eigen::Vector3d {
    const Eigen::Vector3d d = Eigen::Vector3d(P.row(x)) - v;
    return d - n * n.dot(d);
  };
  Eigen::Vector3d left = projected(e.B), right = projected(e.C);
  if (points == CrossEdgePoints::step_zero) {
    const Eigen::Vector3d along = projected(e.A);
    left += along;
    right += along;
  }
  const double lengths = left.norm() * right.norm();
  return lengths > 0.0 ? std::abs(n.dot(left.cross(right))) / lengths : 0.0;
}

}  // namespace

std::vector<int> separate_cross_edge_directions(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F,
                                                const MeshEdges& edges, CrossEdgePoints points, Eigen::MatrixX3d& N,
                                                double min_sine) {
  std::vector<End> ends;  // the ends at vertices that need a new normal
  std::vector<char> flagged(static_cast<std::size_t>(V.rows()), 0);
  std::vector<End> all;
  all.reserve(static_cast<std::size_t>(3 * F.rows()));
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int e = 0; e < 3; ++e) {
      const int g = edges.neighbour(f, e), d = edges.neighbour_edge(f, e);
      const End end{F(f, e), F(f, (e + 1) % 3), F(f, (e + 2) % 3), F(g, (d + 2) % 3)};
      all.push_back(end);
      if (separation(V, end, N.row(end.V).transpose(), points) < min_sine) flagged[static_cast<std::size_t>(end.V)] = 1;
    }
  for (const End& end : all)
    if (flagged[static_cast<std::size_t>(end.V)]) ends.push_back(end);
  std::stable_sort(ends.begin(), ends.end(), [](const End& a, const End& b) { return a.V < b.V; });

  std::vector<int> adjusted;
  for (std::size_t first = 0; first < ends.size();) {
    std::size_t last = first;
    while (last < ends.size() && ends[last].V == ends[first].V) ++last;
    const int v = ends[first].V;
    const Eigen::Vector3d p = V.row(v);
    // The unit normals of the faces at v: (V, A, B) for each end.
    std::vector<Eigen::Vector3d> face_normals;
    for (std::size_t k = first; k < last; ++k) {
      const Eigen::Vector3d n = (Eigen::Vector3d(V.row(ends[k].A)) - p).cross(Eigen::Vector3d(V.row(ends[k].B)) - p);
      if (n.norm() > 0.0) face_normals.push_back(n.normalized());
    }
    const auto lowest_cosine = [&](const Eigen::Vector3d& n) {
      double lowest = std::numeric_limits<double>::infinity();
      for (const Eigen::Vector3d& m : face_normals) lowest = std::min(lowest, n.dot(m));
      return lowest;
    };
    const auto worst_separation = [&](const Eigen::Vector3d& n) {
      double worst = std::numeric_limits<double>::infinity();
      for (std::size_t k = first; k < last; ++k) worst = std::min(worst, separation(V, ends[k], n, points));
      return worst;
    };
    const Eigen::Vector3d present = N.row(v);
    const double floor = std::min(0.05, lowest_cosine(present));
    std::vector<Eigen::Vector3d> candidates;
    Eigen::Vector3d uniform = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& m : face_normals) {
      uniform += m;
      const Eigen::Vector3d towards = m - present * present.dot(m);
      if (towards.norm() == 0.0) continue;
      for (const double degrees : {1.0, 2.0, 4.0, 8.0, 16.0})
        for (const double sign : {1.0, -1.0}) {
          const double a = sign * degrees * kPi / 180.0;
          candidates.push_back((std::cos(a) * present + std::sin(a) * towards.normalized()).normalized());
        }
    }
    if (uniform.norm() > 0.0) candidates.push_back(uniform.normalized());
    Eigen::Vector3d best = present;
    double best_separation = worst_separation(present);
    for (const Eigen::Vector3d& n : candidates) {
      if (lowest_cosine(n) < floor) continue;
      const double s = worst_separation(n);
      if (s > best_separation) {
        best_separation = s;
        best = n;
      }
    }
    if (best != present) {
      N.row(v) = best.transpose();
      adjusted.push_back(v);
    }
    first = last;
  }
  return adjusted;
}

}  // namespace scanstation
