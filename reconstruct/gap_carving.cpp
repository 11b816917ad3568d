#include "reconstruct/gap_carving.h"

#include "core/errors.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace scanstation {

namespace {

// Per point of dt, the square of its spacing: the k-th shortest distinct
// length of its Delaunay edges (k = neighbour ≥ 1; the longest one when it
// has fewer). One pass over the cells.
std::vector<double> point_spacing(const DelaunayComplex<3>& dt, int neighbour) {
  const auto points = static_cast<std::size_t>(dt.points.rows());
  const auto stride = static_cast<std::size_t>(neighbour);
  std::vector<double> shortest(points * stride, std::numeric_limits<double>::infinity());
  // Each cell's four points read once (the complex keeps them by column):
  // a third of the time of reading both ends of every edge.
  for (Eigen::Index c = 0; c < dt.cells.rows(); ++c) {
    int v[4];
    Eigen::Vector3d p[4];
    for (int k = 0; k < 4; ++k) {
      v[k] = dt.cells(c, k);
      p[k] = dt.points.row(v[k]).transpose();
    }
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) {
        const double length = (p[i] - p[j]).squaredNorm();
        offer_length(shortest.data() + static_cast<std::size_t>(v[i]) * stride, stride, length);
        offer_length(shortest.data() + static_cast<std::size_t>(v[j]) * stride, stride, length);
      }
  }
  std::vector<double> spacing(points);
  for (std::size_t v = 0; v < points; ++v) spacing[v] = kth_length(shortest.data() + v * stride, stride);
  return spacing;
}

// The wide-face test of GapOptions: whether the smallest ball holding face i
// of cell c (opposite its vertex i) has a radius of more than options.width
// times the largest spacing at the face's corners.
class WideFaces {
 public:
  WideFaces(const DelaunayComplex<3>& dt, const GapOptions& options)
      : dt_(dt), spacing_(point_spacing(dt, options.neighbour)), width_(options.width * options.width) {}
  bool operator()(Eigen::Index c, int i) const {
    int v[3], n = 0;
    for (int k = 0; k < 4; ++k)
      if (k != i) v[n++] = dt_.cells(c, k);
    const double local = std::max({spacing_[static_cast<std::size_t>(v[0])], spacing_[static_cast<std::size_t>(v[1])],
                                   spacing_[static_cast<std::size_t>(v[2])]});
    return wider_than(dt_.points.row(v[0]).transpose(), dt_.points.row(v[1]).transpose(),
                      dt_.points.row(v[2]).transpose(), local, width_);
  }

 private:
  const DelaunayComplex<3>& dt_;
  std::vector<double> spacing_;
  double width_;
};

}  // namespace

bool wider_than(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& d, double spacing,
                double width) {
  if (!(spacing > 0)) return false;
  // The squared radius of the smallest ball holding the face, in units of
  // the squared spacing (no product overflows at any scale): a quarter of
  // the longest edge's square when the face has an angle of 90° or more,
  // else the circumradius's, |ab|²|ad|²|bd|² / (4 |(b − a) × (d − a)|²).
  // Not the circumradius alone: an almost flat face has a huge one.
  double e[3] = {(b - a).squaredNorm() / spacing, (d - a).squaredNorm() / spacing, (d - b).squaredNorm() / spacing};
  std::sort(e, e + 3);
  // That radius is at most the longest edge over √3 (an equilateral face):
  // most faces are decided here, without the cross product.
  if (e[2] / 3.0 <= width) return false;
  double radius = e[2] / 4.0;
  if (e[0] + e[1] > e[2]) {
    const double cross = (b - a).cross(d - a).squaredNorm() / (spacing * spacing);
    if (cross > 0) radius = e[0] * e[1] * e[2] / (4.0 * cross);
  }
  return radius > width;
}

std::vector<int> gap_depths(const DelaunayComplex<3>& dt, const GapOptions& options) {
  if (options.neighbour < 1) throw InvalidInput("gap carving: the spacing neighbour must be at least 1");
  if (!(options.width > 0)) throw InvalidInput("gap carving: the width factor must be positive");
  if (options.depth < 0) throw InvalidInput("gap carving: the least depth of a gap must not be negative");
  const WideFaces wide(dt, options);

  // Breadth first from the cells with a wide hull face, through wide faces.
  std::vector<int> depth(static_cast<std::size_t>(dt.cells.rows()), -1);
  std::vector<Eigen::Index> queue;
  for (Eigen::Index c = 0; c < dt.cells.rows(); ++c)
    for (int i = 0; i < 4; ++i)
      if (dt.neighbors(c, i) < 0 && wide(c, i)) {
        depth[static_cast<std::size_t>(c)] = 0;
        queue.push_back(c);
        break;
      }
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const Eigen::Index c = queue[head];
    for (int i = 0; i < 4; ++i) {
      const int n = dt.neighbors(c, i);
      if (n >= 0 && depth[static_cast<std::size_t>(n)] < 0 && wide(c, i)) {
        depth[static_cast<std::size_t>(n)] = depth[static_cast<std::size_t>(c)] + 1;
        queue.push_back(n);
      }
    }
  }

  // The reached cells in parts joined by wide faces; a part that nowhere
  // reaches options.depth cells from the hull is dropped (it lies under a
  // few wide faces, not in a gap): on CGAL's handle.off that is worth 1.7
  // points of triangle recall (0.546 → 0.563), and nothing elsewhere.
  std::vector<char> grouped(depth.size(), 0);
  std::vector<Eigen::Index> members;
  for (const Eigen::Index start : queue) {
    if (grouped[static_cast<std::size_t>(start)]) continue;
    members.assign(1, start);
    grouped[static_cast<std::size_t>(start)] = 1;
    int deepest = 0;
    for (std::size_t k = 0; k < members.size(); ++k) {
      const Eigen::Index c = members[k];
      deepest = std::max(deepest, depth[static_cast<std::size_t>(c)]);
      for (int i = 0; i < 4; ++i) {
        const int n = dt.neighbors(c, i);
        if (n >= 0 && depth[static_cast<std::size_t>(n)] >= 0 && !grouped[static_cast<std::size_t>(n)] && wide(c, i)) {
          grouped[static_cast<std::size_t>(n)] = 1;
          members.push_back(n);
        }
      }
    }
    if (deepest < options.depth)
      for (const Eigen::Index c : members) depth[static_cast<std::size_t>(c)] = -1;
  }
  return depth;
}

std::vector<int> carve_first_then(std::vector<int> first, const std::vector<int>& then) {
  const auto ranked = [](const std::vector<int>& ranks) {
    return std::any_of(ranks.begin(), ranks.end(), [](int rank) { return rank >= 0; });
  };
  if (!ranked(then)) return ranked(first) ? first : std::vector<int>{};
  if (!ranked(first)) return then;
  if (first.size() != then.size()) throw InvalidInput("carve order: ranks for different numbers of cells");
  const int after = *std::max_element(first.begin(), first.end()) + 1;
  for (std::size_t c = 0; c < first.size(); ++c)
    if (first[c] < 0 && then[c] >= 0) first[c] = after + then[c];
  return first;
}

}  // namespace scanstation
