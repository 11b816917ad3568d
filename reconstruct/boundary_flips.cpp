#include "reconstruct/boundary_flips.h"

#include "reconstruct/boundary_surface.h"
#include "reconstruct/triangle_set.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <optional>
#include <queue>
#include <tuple>
#include <utility>

namespace scanstation {

namespace {

using Triangle = BoundarySurface::Triangle;

// The measures both criteria read off an edge (a, b) between the faces
// (a, b, c) and (b, a, d).
double area(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r) {
  return 0.5 * (q - p).cross(r - p).norm();
}
double angle(const Eigen::Vector3d& apex, const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
  const Eigen::Vector3d x = u - apex, y = v - apex;
  return std::acos(std::clamp(x.dot(y) / std::sqrt(x.squaredNorm() * y.squaredNorm()), -1.0, 1.0));
}

// The Delaunay rule, as a yes or no: the angles at c and d opposite (a, b)
// sum beyond π (their cotangents sum below zero), those at a and b opposite
// (c, d) do not (so no flip undoes another), and the quad is nearly flat
// (its normals within kFlatDegrees). No acos: the cell flips need no more.
// A degenerate triangle's cotangent is infinite or NaN, and NaN wants nothing.
constexpr double kPi = 3.14159265358979323846;
constexpr double kFlatDegrees = 45.0;
bool delaunay_flip_wanted(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                          const Eigen::Vector3d& d) {
  const auto cot = [](const Eigen::Vector3d& apex, const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
    const Eigen::Vector3d x = u - apex, y = v - apex;
    return x.dot(y) / x.cross(y).norm();
  };
  if (!(cot(c, a, b) + cot(d, b, a) < -1e-9) || !(cot(a, c, d) + cot(b, d, c) > 0)) return false;
  const Eigen::Vector3d n1 = (b - a).cross(c - a), n2 = (a - b).cross(d - b);
  const double dot = n1.dot(n2), cos_flat = std::cos(kFlatDegrees * kPi / 180.0);
  return dot > 0 && dot * dot >= cos_flat * cos_flat * n1.squaredNorm() * n2.squaredNorm();
}

// How much flipping (a, b) to (c, d) is worth under a criterion (> 0: flip).
// Area: the relative drop of the two triangles' area, when at least
// min_gain. Delaunay: by how much the angles opposite (a, b) exceed π, when
// delaunay_flip_wanted.
double flip_gain(FlipCriterion criterion, const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                 const Eigen::Vector3d& d, double min_gain) {
  if (criterion == FlipCriterion::area) {
    const double before = area(a, b, c) + area(b, a, d), after = area(a, d, c) + area(d, b, c);
    return before > 0 && after < before * (1.0 - min_gain) ? 1.0 - after / before : 0.0;
  }
  if (!delaunay_flip_wanted(a, b, c, d)) return 0.0;
  return std::max(0.0, angle(c, a, b) + angle(d, b, a) - kPi);
}

// Edges (a < b) worth a flip by area and, when `delaunay`, by the Delaunay
// rule, found in one pass over the face list alone, so that a surface with
// none costs no spatial index.
struct Candidates {
  std::vector<std::pair<int, int>> by_area, by_delaunay;
};
Candidates candidate_edges(const Eigen::MatrixX3d& P, const Eigen::MatrixX3i& F, bool delaunay, double min_gain) {
  constexpr unsigned kByArea = 1, kByDelaunay = 2;
  const std::vector<MarkedEdge> marked = select_edges(P.rows(), F, [&](int lo, int hi, int c, int d) {
    const Eigen::Vector3d a = P.row(lo).transpose(), b = P.row(hi).transpose(), x = P.row(c).transpose(),
                          y = P.row(d).transpose();
    unsigned mark = flip_gain(FlipCriterion::area, a, b, x, y, min_gain) > 0 ? kByArea : 0;
    if (delaunay && flip_gain(FlipCriterion::area_then_delaunay, a, b, x, y, min_gain) > 0) mark |= kByDelaunay;
    return mark;
  });
  Candidates out;
  for (const MarkedEdge& e : marked) {
    if (e.mark & kByArea) out.by_area.emplace_back(e.lo, e.hi);
    if (e.mark & kByDelaunay) out.by_delaunay.emplace_back(e.lo, e.hi);
  }
  return out;
}

// Which flips need fewer exact tests (see flip_boundary): every triangle of
// the surface is a face of the Delaunay complex except the foreign ones —
// those augmentation carved (§5.4: its tetrahedra are no cells) and those of
// the flips whose tetrahedron was not a cell. A flip whose tetrahedron is a
// cell adds or removes that cell: a Delaunay cell is not flat and holds no
// point, and its new triangles are faces of the complex, which meet the
// other cell faces only in shared vertices and edges — only a foreign
// triangle can cut them, and only those are tested. The cells around each
// point by counting sort (about 25 per point).
class CellFlips {
 public:
  CellFlips(const DelaunayComplex<3>& dt, const CellsAround& around, BoxGrid foreign)
      : dt_(dt), around_(around), foreign_(std::move(foreign)) {}
  bool is_cell(int a, int b, int c, int d) const { return cell_around(a, {b, c, d}); }
  /// The foreign faces, by the surface's face ids (some removed since).
  const BoxGrid& foreign() const { return foreign_; }
  void add_foreign(const BoundarySurface& surface, int f) {
    const Triangle& t = surface.face(f);
    foreign_.insert(f, surface.box({t[0], t[1], t[2]}));
  }
  /// The surface's triangles that are no faces of the complex become
  /// foreign. Those it was built with are looked up among the cells, unless
  /// `built_from_cells` (it was built from the cells' boundary); those of
  /// later edits (augmentation's carves) are taken as foreign unlooked —
  /// one that is a cell face after all only costs its flips the exact
  /// tests, which it passes. Looking up every face took 4–9 ms on CGAL's
  /// largest meshes, about a tenth of the flips.
  void add_foreign_faces(const BoundarySurface& surface, bool built_from_cells) {
    for (std::size_t f = 0; f < surface.face_slots(); ++f) {
      if (!surface.alive(static_cast<int>(f))) continue;
      const Triangle& t = surface.face(static_cast<int>(f));
      const bool edited = f >= surface.built_faces();
      if (edited || (!built_from_cells && !is_face(t[0], t[1], t[2]))) add_foreign(surface, static_cast<int>(f));
    }
  }

 private:
  bool is_face(int a, int b, int c) const { return cell_around(a, {b, c}); }
  // Whether a cell around point a holds every point of `others`.
  bool cell_around(int a, std::initializer_list<int> others) const {
    for (const int cell : around_[static_cast<std::size_t>(a)]) {
      std::size_t found = 0;
      for (int i = 0; i < 4; ++i) found += std::find(others.begin(), others.end(), dt_.cells(cell, i)) != others.end();
      if (found == others.size()) return true;
    }
    return false;
  }
  const DelaunayComplex<3>& dt_;
  const CellsAround& around_;
  BoxGrid foreign_;
};

// Flips by one criterion, largest gain first (area: caps over concavities go
// before the small corrections around them), each under the exact tests.
// cells: given when the surface came as the boundary of a union of Delaunay
// cells (see flip_boundary).
std::size_t flip_pass(BoundarySurface& surface, const std::vector<std::pair<int, int>>& first, FlipCriterion criterion,
                      const TriangleSet& fixed, double min_gain, CellFlips* cells) {
  const auto is_fixed = [&](int f) { return fixed.contains(surface.face(f)); };
  struct Candidate {
    double gain;
    int a, b;
    bool operator<(const Candidate& o) const { return gain != o.gain ? gain < o.gain : std::tie(a, b) > std::tie(o.a, o.b); }
  };
  std::priority_queue<Candidate> edges;
  const auto gain = [&](int a, int b, int c, int d) {
    return flip_gain(criterion, surface.point(a), surface.point(b), surface.point(c), surface.point(d), min_gain);
  };
  const auto gain_of = [&](int a, int b) {
    const auto [f1, c] = surface.face_with(a, b);
    const auto [f2, d] = surface.face_with(b, a);
    return f1 < 0 || f2 < 0 || c == d ? 0.0 : gain(a, b, c, d);
  };
  for (const auto& [a, b] : first)
    if (const double g = gain_of(a, b); g > 0) edges.push({g, a, b});
  // Area flips always lower the area; Delaunay flips on a curved surface
  // have no such potential, so a budget guarantees the end.
  std::size_t flips = 0, budget = 4 * surface.face_count();
  while (!edges.empty() && budget-- > 0) {
    const Candidate top = edges.top();
    edges.pop();
    const int a = top.a, b = top.b;
    const auto [f1, c] = surface.face_with(a, b);
    const auto [f2, d] = surface.face_with(b, a);
    if (f1 < 0 || f2 < 0 || c == d || !(gain(a, b, c, d) > 0) || surface.has_edge(c, d) || is_fixed(f1) || is_fixed(f2))
      continue;
    const Triangle g1{a, d, c}, g2{d, b, c};
    const bool cell = cells && cells->is_cell(a, b, c, d);
    if (cell) {
      if (surface.meets_faces({g1, g2}, {f1, f2}, cells->foreign())) continue;
    } else {
      if (CGAL::orientation(surface.exact(a), surface.exact(b), surface.exact(c), surface.exact(d)) == CGAL::COPLANAR)
        continue;
      if (surface.point_in_tetrahedron(a, b, c, d) || surface.meets_surface({g1, g2}, {f1, f2})) continue;
    }
    surface.remove_face(f1);
    surface.remove_face(f2);
    const int h1 = surface.add_face(g1), h2 = surface.add_face(g2);
    if (cells && !cell) {
      cells->add_foreign(surface, h1);
      cells->add_foreign(surface, h2);
    }
    ++flips;
    for (const auto& [u, v] : {std::pair{a, d}, std::pair{d, b}, std::pair{b, c}, std::pair{c, a}}) {
      const double g = gain_of(std::min(u, v), std::max(u, v));
      if (g > 0) edges.push({g, std::min(u, v), std::max(u, v)});
    }
  }
  return flips;
}

// The pass of flip_delaunay_cells: it changes the kept flags only, never
// the complex.
class CellToggles {
 public:
  CellToggles(const DelaunayComplex<3>& dt, std::vector<char>& kept, TriangleSet fixed)
      : dt_(dt), kept_(kept), fixed_(std::move(fixed)), points_(static_cast<std::size_t>(dt.points.rows())) {
    // A point's coordinates together (the complex keeps them by column).
    for (std::size_t v = 0; v < points_.size(); ++v) points_[v] = dt.points.row(static_cast<Eigen::Index>(v)).transpose();
  }

  // A flip is a cell with exactly two faces on the boundary: they share an
  // edge (a, b), and toggling the cell flips it to (c, d). One sweep over
  // the cells in storage order (by their last point, along the insertion's
  // Hilbert curve: nearby cells are near in memory) makes each flip the
  // rule allows as it is met (Lawson's order rather than the largest excess
  // first: no queue of gains, and the walks stay local). A toggle changes
  // which faces of its four neighbours are on the boundary, and takes (a, b)
  // off it, which a cell around (a, b) may have waited for; those cells go
  // on a stack and are tried at once, while they are still in the caches. So no flip is left at the end, unless 8
  // flips per point were made.
  std::size_t run() {
    // 4 flips per boundary triangle: a closed genus-0 surface through at
    // most all the points has fewer than 2 triangles per point.
    budget_ = 8 * static_cast<std::size_t>(dt_.points.rows());
    queued_.assign(static_cast<std::size_t>(cells()), 0);
    for (int c = 0; c < cells() && budget_ > 0; ++c) {
      try_cell(c);
      while (!stack_.empty() && budget_ > 0) {
        const int x = stack_.back();
        stack_.pop_back();
        queued_[static_cast<std::size_t>(x)] = 0;
        try_cell(x);
      }
    }
    return flips_;
  }

 private:
  // Faces (a, b, c) and (b, a, d), counter-clockwise from outside, and the
  // cell (a, b, c, d) whose toggling flips (a, b) to (c, d).
  struct Flip {
    int cell, a, b, c, d;
  };
  int cells() const { return static_cast<int>(dt_.cells.rows()); }

  void try_cell(int t) {
    const auto flip = flip_of(t);
    if (!flip || !allowed(*flip)) return;
    kept_[static_cast<std::size_t>(t)] = !kept_[static_cast<std::size_t>(t)];
    ++flips_;
    --budget_;
    for (int j = 0; j < 4; ++j) again(dt_.neighbors(t, j));
    around(t, flip->a, flip->b, [&](int x) { again(x); });
  }
  void again(int c) {
    if (c < 0 || queued_[static_cast<std::size_t>(c)]) return;
    queued_[static_cast<std::size_t>(c)] = 1;
    stack_.push_back(c);
  }

  // The flip of cell t, if exactly two of its faces are on the boundary.
  std::optional<Flip> flip_of(int t) const {
    int off[2], n = 0;  // local vertices opposite the boundary faces: d, then c
    for (int i = 0; i < 4; ++i)
      if (boundary_face(t, i)) {
        if (n == 2) return std::nullopt;
        off[n++] = i;
      }
    if (n != 2) return std::nullopt;
    // Orient: the face opposite d is counter-clockwise seen from outside
    // the cell (kFace3), so from outside the solid when the cell is kept.
    const int d3 = dt_.cells(t, off[0]), c3 = dt_.cells(t, off[1]);
    const int* f = kFace3[off[0]];
    int tri[3] = {dt_.cells(t, f[0]), dt_.cells(t, f[1]), dt_.cells(t, f[2])};
    if (!inside(t)) std::swap(tri[1], tri[2]);
    int j = 0;
    while (tri[(j + 2) % 3] != c3) ++j;  // the edge's ends in face order: (a, b, c3)
    return Flip{t, tri[j], tri[(j + 1) % 3], c3, d3};
  }

  bool inside(int c) const { return c >= 0 && kept_[static_cast<std::size_t>(c)]; }
  const Eigen::Vector3d& point(int v) const { return points_[static_cast<std::size_t>(v)]; }

  // The two faces of cell c holding its edge (u, v): opposite its other
  // two vertices, given as local indices.
  void off_edge(int c, int u, int v, int (&k)[2]) const {
    int n = 0;
    for (int i = 0; i < 4; ++i)
      if (dt_.cells(c, i) != u && dt_.cells(c, i) != v) k[n++] = i;
  }
  bool boundary_face(int c, int i) const { return inside(c) != inside(dt_.neighbors(c, i)); }

  // Walks the ring of cells around the edge (u, v) of cell c (as
  // constriction's §5.3 test): see walk_ring.
  template <typename Step>
  bool walk_around(int c, int u, int v, Step&& step) const {
    int at[2];
    off_edge(c, u, v, at);
    return walk_ring(dt_, c, u, v, at, step);
  }
  // Whether a boundary face holds the edge (u, v) of cell c.
  bool edge_on_boundary(int c, int u, int v) const {
    return !walk_around(c, u, v, [&](int x, int y) { return inside(x) == inside(y); });
  }
  // Calls visit(x) for every other cell x around the edge (u, v) of cell c.
  template <typename Visit>
  void around(int c, int u, int v, Visit&& visit) const {
    walk_around(c, u, v, [&](int, int y) {
      if (y >= 0 && y != c) visit(y);
      return true;
    });
  }

  // A flip worth making and allowed: (c, d) not on the boundary yet (it
  // would meet four boundary faces), neither face kept (§5.7).
  bool allowed(const Flip& f) const {
    return delaunay_flip_wanted(point(f.a), point(f.b), point(f.c), point(f.d)) && !is_fixed(f.a, f.b, f.c) &&
           !is_fixed(f.b, f.a, f.d) && !edge_on_boundary(f.cell, f.c, f.d);
  }

  bool is_fixed(int a, int b, int c) const { return fixed_.contains(a, b, c); }

  const DelaunayComplex<3>& dt_;
  std::vector<char>& kept_;
  TriangleSet fixed_;
  std::vector<Eigen::Vector3d> points_;
  std::vector<char> queued_;  // on the stack
  std::vector<int> stack_;
  std::size_t flips_ = 0, budget_ = 0;
};

}  // namespace

std::size_t flip_delaunay_cells(const DelaunayComplex<3>& complex, std::vector<char>& kept, const Eigen::MatrixXi& keep) {
  return CellToggles(complex, kept, TriangleSet(keep)).run();
}

std::size_t flip_boundary(const Eigen::MatrixX3d& points, Eigen::MatrixX3i& boundary, FlipCriterion criterion,
                          const Eigen::MatrixXi& keep, double min_gain, const DelaunayComplex<3>* cells,
                          std::optional<BoundarySurface>* given, std::optional<CellsAround>* around,
                          std::shared_ptr<const PointTree> tree) {
  const bool delaunay = criterion == FlipCriterion::area_then_delaunay;
  Candidates candidates = candidate_edges(points, boundary, delaunay, min_gain);
  if (candidates.by_area.empty() && candidates.by_delaunay.empty()) return 0;
  std::optional<BoundarySurface> own;
  std::optional<BoundarySurface>& held = given ? *given : own;
  const bool edited_surface = held.has_value();  // built from the cells' boundary, then augmented
  if (!held) held.emplace(points, boundary, std::move(tree));
  BoundarySurface& surface = *held;
  const TriangleSet fixed(keep);
  std::optional<CellFlips> cell_flips;
  std::optional<CellsAround> own_around;
  if (cells) {
    std::optional<CellsAround>& shared = around ? *around : own_around;
    if (!shared) shared.emplace(*cells);
    cell_flips.emplace(*cells, *shared, surface.empty_grid());
    cell_flips->add_foreign_faces(surface, edited_surface);
  }
  CellFlips* untested = cell_flips ? &*cell_flips : nullptr;
  const std::size_t slots = surface.face_slots();
  std::size_t flips = flip_pass(surface, candidates.by_area, FlipCriterion::area, fixed, min_gain, untested);
  if (delaunay) {
    // The Delaunay candidates of the surface the area flips left: an edge
    // whose two faces the area flips kept has the gain it had, any other is
    // an edge of a face they made (ids are never reused).
    std::vector<std::pair<int, int>>& edges = candidates.by_delaunay;
    for (std::size_t f = slots; f < surface.face_slots(); ++f) {
      if (!surface.alive(static_cast<int>(f))) continue;
      const Triangle& t = surface.face(static_cast<int>(f));
      for (int k = 0; k < 3; ++k) edges.emplace_back(std::minmax(t[k], t[(k + 1) % 3]));
    }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    flips += flip_pass(surface, edges, criterion, fixed, min_gain, untested);
  }
  boundary = surface.boundary();
  return flips;
}

}  // namespace scanstation
