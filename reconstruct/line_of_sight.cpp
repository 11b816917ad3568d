#include "reconstruct/line_of_sight.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>

namespace scanstation {

namespace {

using Point = CGAL::Exact_predicates_inexact_constructions_kernel::Point_3;

// What every walk reads: the complex, its points as the predicates take
// them (each point's coordinates together: a walk reads four corners a
// cell, and a row of the column-major input is three scattered loads), and
// a cell at each point.
struct SightData {
  SightData(const DelaunayComplex<3>& dt, const Eigen::MatrixX3d& P, Eigen::Index whole_stars)
      : dt(dt), whole_stars(whole_stars), cell_of(static_cast<std::size_t>(P.rows()), -1) {
    points.reserve(static_cast<std::size_t>(P.rows()));
    for (Eigen::Index i = 0; i < P.rows(); ++i) points.emplace_back(P(i, 0), P(i, 1), P(i, 2));
    for (Eigen::Index c = 0; c < dt.cells.rows(); ++c)
      for (int i = 0; i < 4; ++i) cell_of[static_cast<std::size_t>(dt.cells(c, i))] = static_cast<int>(c);
  }
  const DelaunayComplex<3>& dt;
  std::vector<Point> points;
  Eigen::Index whole_stars;
  std::vector<int> cell_of;
};

// A depth (−1: no line crossed the cell yet) lowered to d.
void keep_least(int& depth, int d) {
  if (depth < 0 || d < depth) depth = d;
}

// One thread's walks, with its own scratch.
class SightWalk {
 public:
  explicit SightWalk(const SightData& data)
      : dt_(data.dt), points_(data.points), whole_stars_(data.whole_stars), cell_of_(data.cell_of) {}

  void walk(const SightLine& line, std::vector<int>& depth) {
    if (line.point < 0 || static_cast<std::size_t>(line.point) >= points_.size() || !line.viewpoint.allFinite()) return;
    const Point& p = points_[static_cast<std::size_t>(line.point)];
    const Point q(line.viewpoint.x(), line.viewpoint.y(), line.viewpoint.z());
    int cell = entry_cell(line.point, q);
    path_.clear();
    // A straight segment crosses each cell once; the bound only guards
    // against a cycle of grazing choices. `entry`: the face the walk came in
    // through (q was strictly beyond it in the cell before, so it is
    // strictly on its inner side here, and no way out).
    for (int steps = 0, entry = -1; cell >= 0 && steps < dt_.cells.rows(); ++steps) {
      path_.push_back(cell);
      const Corners v = corners(cell);
      int exit = -1, beyond = -1;
      for (int k = 0; k < 4; ++k) {
        if (k == entry || side(v, k, q) >= 0) continue;  // q is not past face k (nor past a face through p: the entry cone)
        if (beyond < 0) beyond = k;
        if (crosses_face(p, q, v, k)) {
          exit = k;
          break;
        }
      }
      if (exit < 0) exit = beyond;
      if (exit < 0) break;  // q lies in this cell
      const int next = dt_.neighbors(cell, exit);
      if (next >= 0) {
        entry = 0;
        while (dt_.neighbors(next, entry) != cell) ++entry;
      }
      cell = next;
    }
    for (std::size_t k = 0; k < path_.size(); ++k)
      keep_least(depth[static_cast<std::size_t>(path_[k])], static_cast<int>(path_.size() - 1 - k));
  }

 private:
  const Point& corner(int cell, int k) const { return points_[static_cast<std::size_t>(dt_.cells(cell, k))]; }

  // A cell's corners, read once per cell and shared by its tests.
  using Corners = std::array<Point, 4>;
  Corners corners(int cell) const { return {corner(cell, 0), corner(cell, 1), corner(cell, 2), corner(cell, 3)}; }

  // Orientation of the cell with its vertex k replaced by x: > 0 when x is on
  // the same side of the face opposite k as that vertex (cells are
  // positively oriented).
  static int side(Corners v, int k, const Point& x) {
    v[static_cast<std::size_t>(k)] = x;
    return static_cast<int>(CGAL::orientation(v[0], v[1], v[2], v[3]));
  }
  int side(int cell, int k, const Point& x) const { return side(corners(cell), k, x); }

  // Whether the line through p and q meets the face opposite k of the cell
  // with corners v (its interior or boundary): the three edge orientations
  // agree.
  static bool crosses_face(const Point& p, const Point& q, const Corners& v, int k) {
    const Point* f[3];
    for (int j = 0, m = 0; j < 4; ++j)
      if (j != k) f[m++] = &v[static_cast<std::size_t>(j)];
    const int s0 = CGAL::orientation(p, q, *f[0], *f[1]), s1 = CGAL::orientation(p, q, *f[1], *f[2]),
              s2 = CGAL::orientation(p, q, *f[2], *f[0]);
    return (s0 >= 0 && s1 >= 0 && s2 >= 0) || (s0 <= 0 && s1 <= 0 && s2 <= 0);
  }

  // The cell around the point whose cone at it holds the direction towards
  // q: q on the inner side (or the plane) of the three faces through it.
  // Found by walking from cone to cone across a face through the point that
  // has q beyond it. Where such a face is a convex hull face (no neighbour,
  // the point's star whole), q lies outside the hull's cone at the point,
  // which the cones of its cells fill: no cell holds the direction. Only a
  // walk that cannot go on (a star cut off at the edge of a part of a
  // triangulation, or a cycle) searches the whole star. The search alone
  // took about 44 orientation tests per line on a dense scan (some 25 cells
  // around a point), ten times the walk along the line after it.
  int entry_cell(int point, const Point& q) {
    const int first = cell_of_[static_cast<std::size_t>(point)];
    if (first < 0) return -1;
    const bool whole = point < whole_stars_;
    for (int c = first, previous = -1, steps = 0; steps < kWalkSteps; ++steps) {
      int next = -1;
      bool inside = true;
      for (int j = 0; j < 4 && next < 0; ++j) {
        if (dt_.cells(c, j) == point || side(c, j, q) >= 0) continue;
        inside = false;
        const int n = dt_.neighbors(c, j);
        if (n < 0 && whole) return -1;
        if (n >= 0 && n != previous) next = n;
      }
      if (inside) return c;
      if (next < 0) break;
      previous = c;
      c = next;
    }
    return search_star(point, q);
  }
  static constexpr int kWalkSteps = 64;

  // The same by trying every cell around the point, nearest first.
  int search_star(int point, const Point& q) {
    const int first = cell_of_[static_cast<std::size_t>(point)];
    star_.clear();
    star_.push_back(first);
    for (std::size_t n = 0; n < star_.size(); ++n) {
      const int c = star_[n];
      bool inside = true;
      for (int j = 0; j < 4; ++j) {
        if (dt_.cells(c, j) == point) continue;
        if (side(c, j, q) < 0) inside = false;
        const int next = dt_.neighbors(c, j);  // across a face through the point
        if (next >= 0 && std::find(star_.begin(), star_.end(), next) == star_.end()) star_.push_back(next);
      }
      if (inside) return c;
    }
    return -1;  // q is behind the hull at this point: nothing to carve
  }

  const DelaunayComplex<3>& dt_;
  const std::vector<Point>& points_;
  Eigen::Index whole_stars_;
  const std::vector<int>& cell_of_;
  std::vector<int> star_, path_;
};

}  // namespace

std::vector<int> line_of_sight_depths(const DelaunayComplex<3>& dt, const Eigen::MatrixX3d& points,
                                      const std::vector<SightLine>& lines, Eigen::Index whole_stars) {
  std::vector<int> depth(static_cast<std::size_t>(dt.cells.rows()), -1);
  const SightData data(dt, points, whole_stars);
  // A cell's depth is the least over the lines that cross it, whichever
  // walks them: the lines go to both cores in blocks, each thread keeps its
  // own depths, and those are merged by the same least.
  constexpr std::size_t kBlock = 256;
  if (lines.size() < 8 * kBlock) {
    SightWalk walk(data);
    for (const SightLine& line : lines) walk.walk(line, depth);
    return depth;
  }
  struct Local {
    explicit Local(const SightData& data) : walk(data), depth(static_cast<std::size_t>(data.dt.cells.rows()), -1) {}
    SightWalk walk;
    std::vector<int> depth;
  };
  tbb::enumerable_thread_specific<Local> local([&] { return Local(data); });
  const auto walk_block = [&](const tbb::blocked_range<std::size_t>& r) {
    Local& mine = local.local();
    for (std::size_t i = r.begin(); i < r.end(); ++i) mine.walk.walk(lines[i], mine.depth);
  };
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, lines.size(), kBlock), walk_block);
  for (const Local& mine : local)
    for (std::size_t c = 0; c < depth.size(); ++c)
      if (mine.depth[c] >= 0) keep_least(depth[c], mine.depth[c]);
  return depth;
}

}  // namespace scanstation
