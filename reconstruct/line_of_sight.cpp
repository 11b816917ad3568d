#include "reconstruct/line_of_sight.h"

#include "reconstruct/spatial_order.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <utility>

namespace scanstation {

namespace {

using Point = CGAL::Exact_predicates_inexact_constructions_kernel::Point_3;

// A cell's corners and neighbours in one 32-byte row. A walk steps to a new
// cell at every test, far from the last in memory: in the complex's two
// arrays its eight numbers are two cache lines (and were eight while the
// arrays were stored by column: on the 100-step chalice scan, most of the
// walks' time was waiting for them).
struct alignas(32) CellRow {
  std::array<int, 4> vertex, neighbor;
};

// What every walk reads: the complex's cells by row, its points as the
// predicates take them (each point's coordinates together, for the same
// reason), and a cell at each point.
struct SightData {
  SightData(const DelaunayComplex<3>& dt, const Eigen::MatrixX3d& P, Eigen::Index whole_stars)
      : cells(static_cast<std::size_t>(dt.cells.rows())), whole_stars(whole_stars),
        cell_of(static_cast<std::size_t>(P.rows()), -1) {
    points.reserve(static_cast<std::size_t>(P.rows()));
    for (Eigen::Index i = 0; i < P.rows(); ++i) {
      points.emplace_back(P(i, 0), P(i, 1), P(i, 2));
      box += points.back().bbox();
    }
    for (Eigen::Index c = 0; c < dt.cells.rows(); ++c)
      for (int i = 0; i < 4; ++i) {
        cells[static_cast<std::size_t>(c)].vertex[static_cast<std::size_t>(i)] = dt.cells(c, i);
        cells[static_cast<std::size_t>(c)].neighbor[static_cast<std::size_t>(i)] = dt.neighbors(c, i);
      }
    for (std::size_t c = 0; c < cells.size(); ++c)
      for (const int v : cells[c].vertex) cell_of[static_cast<std::size_t>(v)] = static_cast<int>(c);
  }
  std::vector<CellRow> cells;
  std::vector<Point> points;
  CGAL::Bbox_3 box;  // of the points
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
      : cells_(data.cells), points_(data.points), box_(data.box), whole_stars_(data.whole_stars), cell_of_(data.cell_of) {}

  void walk(const SightLine& line, std::vector<int>& depth) {
    if (line.point < 0 || static_cast<std::size_t>(line.point) >= points_.size() || !line.viewpoint.allFinite()) return;
    const Point& p = points_[static_cast<std::size_t>(line.point)];
    const Point q(line.viewpoint.x(), line.viewpoint.y(), line.viewpoint.z());
    // A viewpoint outside the points' box lies in no cell, so past the way
    // out of every cell the line crosses from the inside of its entry face
    // (the line leaves the cell before it gets to q): exit_through needs no
    // test of q then. The comparisons are exact.
    const bool outside = q.x() < box_.xmin() || q.x() > box_.xmax() || q.y() < box_.ymin() || q.y() > box_.ymax() ||
                         q.z() < box_.zmin() || q.z() > box_.zmax();
    int cell = entry_cell(line.point, q);
    path_.clear();
    // A straight segment crosses each cell once; the bound only guards
    // against a cycle of grazing choices. `entry`: the face the walk came in
    // through (q was strictly beyond it in the cell before, so it is
    // strictly on its inner side here, and no way out). `through`: that
    // face when the line crosses its interior, with its edges' sides.
    Crossing through;
    for (int steps = 0, entry = -1; cell >= 0 && steps < static_cast<int>(cells_.size()); ++steps) {
      path_.push_back(cell);
      int exit = entry >= 0 && through.valid() ? exit_through(p, q, outside, cell, entry, through) : kUndecided;
      if (exit == kUndecided) exit = exit_by_faces(p, q, cell, entry, through);
      if (exit < 0) break;  // q lies in this cell
      const int next = neighbor(cell, exit);
      if (next >= 0) {
        entry = 0;
        while (neighbor(next, entry) != cell) ++entry;
      }
      cell = next;
    }
    for (std::size_t k = 0; k < path_.size(); ++k)
      keep_least(depth[static_cast<std::size_t>(path_[k])], static_cast<int>(path_.size() - 1 - k));
  }

 private:
  int vertex(int cell, int k) const { return cells_[static_cast<std::size_t>(cell)].vertex[static_cast<std::size_t>(k)]; }
  int neighbor(int cell, int k) const { return cells_[static_cast<std::size_t>(cell)].neighbor[static_cast<std::size_t>(k)]; }
  const Point& corner(int cell, int k) const { return points_[static_cast<std::size_t>(vertex(cell, k))]; }

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

  // A face the line crosses in its interior, as its vertices (u0, u1, u2)
  // and the side every edge u_i u_(i+1) has of the line: orientation(p, q,
  // u_i, u_(i+1)) = sigma for all three (sigma 0: none known).
  struct Crossing {
    std::array<int, 3> u{};
    int sigma = 0;
    bool valid() const { return sigma != 0; }
  };
  static constexpr int kUndecided = -2;

  int edge_side(const Point& p, const Point& q, int a, int b) const {
    return static_cast<int>(CGAL::orientation(p, q, points_[static_cast<std::size_t>(a)], points_[static_cast<std::size_t>(b)]));
  }

  // The way out of a cell the line entered through the interior of face
  // `entry` (the face (a, b, c) of `through`), from the sides of the edges
  // to the fourth vertex d alone: viewed along the line, the line's point
  // lies inside triangle abc and inside exactly one of bcd, cad, abd, which
  // the sides of ad, bd, cd tell (two tests, a third when the answer is
  // abd, to see that it is no tie). That face is the one the face tests
  // would find (the line meets no other face of the cell); q strictly
  // beyond it goes on through it (`through` then becomes it), else q is in
  // the cell (−1); `q_outside`: q lies outside the points' box, so beyond.
  // A zero side (the line meets an edge or the line through one) leaves
  // the choice to the face tests: kUndecided.
  int exit_through(const Point& p, const Point& q, bool q_outside, int cell, int entry, Crossing& through) const {
    const int sigma = through.sigma;
    const auto [a, b, c] = through.u;
    const int d = vertex(cell, entry);
    // The faces opposite a, b, c as triangles whose edges keep sigma.
    int opposite, x, y;
    const int Z = edge_side(p, q, c, d);
    if (Z == 0) return kUndecided;
    if (Z == sigma) {
      const int Y = edge_side(p, q, b, d);
      if (Y == 0) return kUndecided;
      if (Y == -sigma) {
        opposite = a, x = b, y = c;  // bcd
      } else {
        if (edge_side(p, q, a, d) != -sigma) return kUndecided;
        opposite = c, x = a, y = b;  // abd
      }
    } else {
      const int X = edge_side(p, q, a, d);
      if (X == 0) return kUndecided;
      if (X == sigma) {
        opposite = b, x = c, y = a;  // cad
      } else {
        if (edge_side(p, q, b, d) != sigma) return kUndecided;
        opposite = c, x = a, y = b;  // abd
      }
    }
    int k = 0;
    while (vertex(cell, k) != opposite) ++k;
    if (!q_outside && side(cell, k, q) >= 0) return -1;  // q is not past the way out: it lies in the cell
    through.u = {x, y, d};
    return k;
  }

  // The way out by testing the faces: among those q is strictly beyond (not
  // the entry face), the first the line meets (a line through an edge or a
  // vertex meets several), else the first of them; −1 when there is none (q
  // lies in the cell). `through` becomes the face taken when the line
  // crosses its interior, else unknown.
  int exit_by_faces(const Point& p, const Point& q, int cell, int entry, Crossing& through) const {
    const Corners v = corners(cell);
    int beyond = -1;
    through.sigma = 0;
    for (int k = 0; k < 4; ++k) {
      if (k == entry || side(v, k, q) >= 0) continue;  // q is not past face k (nor past a face through p: the entry cone)
      if (beyond < 0) beyond = k;
      if (crosses_face(p, q, cell, v, k, through)) return k;
    }
    return beyond;
  }

  // Whether the line through p and q meets the face opposite k of the cell
  // with corners v (its interior or boundary): the three edge orientations
  // agree. When they agree and none is 0, `through` records the face.
  bool crosses_face(const Point& p, const Point& q, int cell, const Corners& v, int k, Crossing& through) const {
    int f[3];
    for (int j = 0, m = 0; j < 4; ++j)
      if (j != k) f[m++] = j;
    const auto at = [&](int i) -> const Point& { return v[static_cast<std::size_t>(f[i])]; };
    const int s0 = CGAL::orientation(p, q, at(0), at(1)), s1 = CGAL::orientation(p, q, at(1), at(2)),
              s2 = CGAL::orientation(p, q, at(2), at(0));
    if (s0 != 0 && s0 == s1 && s1 == s2) {
      through.u = {vertex(cell, f[0]), vertex(cell, f[1]), vertex(cell, f[2])};
      through.sigma = s0;
    }
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
        if (vertex(c, j) == point || side(c, j, q) >= 0) continue;
        inside = false;
        const int n = neighbor(c, j);
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
        if (vertex(c, j) == point) continue;
        if (side(c, j, q) < 0) inside = false;
        const int next = neighbor(c, j);  // across a face through the point
        if (next >= 0 && std::find(star_.begin(), star_.end(), next) == star_.end()) star_.push_back(next);
      }
      if (inside) return c;
    }
    return -1;  // q is behind the hull at this point: nothing to carve
  }

  const std::vector<CellRow>& cells_;
  const std::vector<Point>& points_;
  CGAL::Bbox_3 box_;
  Eigen::Index whole_stars_;
  const std::vector<int>& cell_of_;
  std::vector<int> star_, path_;
};

// The lines sorted by their points' places along a Morton curve over the
// points' box (a 2^10 grid: fine enough that a grid cell holds a few
// lines), each key packed with its line's number; lines without a point
// last.
std::vector<std::uint32_t> spatial_order(const SightData& data, const std::vector<SightLine>& lines) {
  const CGAL::Bbox_3& box = data.box;
  constexpr double kCells = 1024.0;
  const double size = std::max({box.xmax() - box.xmin(), box.ymax() - box.ymin(), box.zmax() - box.zmin()});
  const double scale = size > 0.0 ? (kCells - 1.0) / size : 0.0;
  const auto grid = [&](double x, double low) { return static_cast<std::uint32_t>((x - low) * scale); };
  std::vector<std::uint64_t> keyed(lines.size());
  for (std::size_t i = 0; i < lines.size(); ++i) {
    std::uint64_t key = std::uint64_t{1} << 31;  // past every point's key
    if (const int point = lines[i].point; point >= 0 && static_cast<std::size_t>(point) < data.points.size()) {
      const Point& p = data.points[static_cast<std::size_t>(point)];
      key = morton_index_3(grid(p.x(), box.xmin()), grid(p.y(), box.ymin()), grid(p.z(), box.zmin()));
    }
    keyed[i] = key << 32 | i;
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<std::uint32_t> order(lines.size());
  for (std::size_t k = 0; k < keyed.size(); ++k) order[k] = static_cast<std::uint32_t>(keyed[k]);
  return order;
}

}  // namespace

std::vector<int> line_of_sight_depths(const DelaunayComplex<3>& dt, const Eigen::MatrixX3d& points,
                                      const std::vector<SightLine>& lines, Eigen::Index whole_stars) {
  std::vector<int> depth(static_cast<std::size_t>(dt.cells.rows()), -1);
  const SightData data(dt, points, whole_stars);
  // A cell's depth is the least over the lines that cross it, whichever
  // walks them: the lines go to both cores in blocks, each thread keeps its
  // own depths, and those are merged by the same least.
  //
  // The lines are walked in the order of their points along a Morton
  // curve: lines walked one after another then start near each other and,
  // towards nearby viewpoints, cross many of the same cells while those are
  // still cached (the cells of a local complex lie in CGAL's storage order,
  // all over memory).
  const std::vector<std::uint32_t> order = spatial_order(data, lines);
  const auto line = [&](std::size_t k) -> const SightLine& { return lines[order[k]]; };
  constexpr std::size_t kBlock = 256;
  if (lines.size() < 8 * kBlock) {
    SightWalk walk(data);
    for (std::size_t k = 0; k < lines.size(); ++k) walk.walk(line(k), depth);
    return depth;
  }
  struct Local {
    explicit Local(const SightData& data) : walk(data), depth(data.cells.size(), -1) {}
    SightWalk walk;
    std::vector<int> depth;
  };
  tbb::enumerable_thread_specific<Local> local([&] { return Local(data); });
  const auto walk_block = [&](const tbb::blocked_range<std::size_t>& r) {
    Local& mine = local.local();
    for (std::size_t k = r.begin(); k < r.end(); ++k) mine.walk.walk(line(k), mine.depth);
  };
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, lines.size(), kBlock), walk_block);
  for (const Local& mine : local)
    for (std::size_t c = 0; c < depth.size(); ++c)
      if (mine.depth[c] >= 0) keep_least(depth[c], mine.depth[c]);
  return depth;
}

}  // namespace scanstation
