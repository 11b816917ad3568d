#include "reconstruct/boundary_flips.h"

#include "reconstruct/boundary_surface.h"

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

// Vertices of the face opposite local vertex i, counter-clockwise seen from
// outside a positively oriented tetrahedron (as in constriction).
constexpr int kFace3[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};

// The measures both criteria read off an edge (a, b) between the faces
// (a, b, c) and (b, a, d).
double area(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r) {
  return 0.5 * (q - p).cross(r - p).norm();
}
double angle(const Eigen::Vector3d& apex, const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
  const Eigen::Vector3d x = u - apex, y = v - apex;
  return std::acos(std::clamp(x.dot(y) / std::sqrt(x.squaredNorm() * y.squaredNorm()), -1.0, 1.0));
}

// How much flipping (a, b) to (c, d) is worth under a criterion (> 0: flip).
// Area: the relative drop of the two triangles' area, when at least
// min_gain. Delaunay: by how much the angles opposite (a, b) exceed π, when
// the quad is nearly flat (its normals within kFlatDegrees) and the new edge
// is locally Delaunay itself (so no flip undoes another).
constexpr double kPi = 3.14159265358979323846;
constexpr double kFlatDegrees = 45.0;
double flip_gain(FlipCriterion criterion, const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                 const Eigen::Vector3d& d, double min_gain) {
  if (criterion == FlipCriterion::area) {
    const double before = area(a, b, c) + area(b, a, d), after = area(a, d, c) + area(d, b, c);
    return before > 0 && after < before * (1.0 - min_gain) ? 1.0 - after / before : 0.0;
  }
  const double before = angle(c, a, b) + angle(d, b, a);
  if (!(before > kPi + 1e-9) || !(angle(a, c, d) + angle(b, d, c) < kPi)) return 0.0;
  const Eigen::Vector3d n1 = (b - a).cross(c - a), n2 = (a - b).cross(d - b);
  if (n1.dot(n2) < std::cos(kFlatDegrees * kPi / 180.0) * n1.norm() * n2.norm()) return 0.0;
  return before - kPi;
}

// Edges (a < b) worth a flip, found from the face list alone, so that a
// surface with none costs two linear passes and no spatial index.
std::vector<std::pair<int, int>> candidate_edges(const Eigen::MatrixX3d& P, const Eigen::MatrixX3i& F,
                                                 FlipCriterion criterion, double min_gain) {
  std::vector<std::pair<int, int>> out;
  for_each_edge(P.rows(), F, [&](int lo, int hi, int c, int d) {
    if (flip_gain(criterion, P.row(lo).transpose(), P.row(hi).transpose(), P.row(c).transpose(), P.row(d).transpose(),
                  min_gain) > 0)
      out.emplace_back(lo, hi);
  });
  return out;
}

// The §5.7 kept faces, each with its vertices sorted, in sorted order.
std::vector<Triangle> sorted_triangles(const Eigen::MatrixXi& keep) {
  std::vector<Triangle> out;
  for (Eigen::Index k = 0; k < keep.rows(); ++k) {
    Triangle t{keep(k, 0), keep(k, 1), keep(k, 2)};
    std::sort(t.begin(), t.end());
    out.push_back(t);
  }
  std::sort(out.begin(), out.end());
  return out;
}

// Which flips need no exact test (see flip_boundary): every triangle of the
// surface is a face of the Delaunay complex except the foreign ones — those
// augmentation carved (§5.4: its tetrahedra are no cells) and those of the
// flips whose tetrahedron was not a cell. A flip whose tetrahedron is a cell
// whose box misses every foreign box adds or removes that cell: its new
// triangles are faces of the complex and meet the other cell faces only in
// shared vertices and edges, no foreign triangle comes near, and a Delaunay
// cell holds no point. The cells around each point by counting sort (about
// 25 per point).
class CellFlips {
 public:
  CellFlips(const DelaunayComplex<3>& dt, BoxGrid foreign) : dt_(dt), around_(dt), foreign_(std::move(foreign)) {}
  /// Flipping (a, b) to (c, d) adds or removes a cell far from foreign flips.
  bool toggles(int a, int b, int c, int d) const {
    if (!is_cell(a, b, c, d)) return false;
    Eigen::AlignedBox3d box;
    for (const int v : {a, b, c, d}) box.extend(dt_.points.row(v).transpose());
    return foreign_.visit(box, [](int) { return false; });
  }
  void add_foreign(const Eigen::AlignedBox3d& box) { foreign_.insert(foreign_count_++, box); }
  /// The surface's triangles that are no faces of the complex become foreign.
  void add_foreign_faces(const BoundarySurface& surface) {
    for (std::size_t f = 0; f < surface.face_slots(); ++f) {
      const Triangle& t = surface.face(static_cast<int>(f));
      if (surface.alive(static_cast<int>(f)) && !is_face(t[0], t[1], t[2])) add_foreign(surface.box({t[0], t[1], t[2]}));
    }
  }

 private:
  bool is_face(int a, int b, int c) const { return cell_around(a, {b, c}); }
  bool is_cell(int a, int b, int c, int d) const { return cell_around(a, {b, c, d}); }
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
  CellsAround around_;
  BoxGrid foreign_;
  int foreign_count_ = 0;
};

// Flips by one criterion, largest gain first (area: caps over concavities go
// before the small corrections around them), each under the exact tests.
// cells: given when the surface came as the boundary of a union of Delaunay
// cells (see flip_boundary).
std::size_t flip_pass(BoundarySurface& surface, const std::vector<std::pair<int, int>>& first, FlipCriterion criterion,
                      const std::vector<Triangle>& fixed, double min_gain, CellFlips* cells) {
  const auto is_fixed = [&](int f) {
    Triangle t = surface.face(f);
    std::sort(t.begin(), t.end());
    return std::binary_search(fixed.begin(), fixed.end(), t);
  };
  struct Candidate {
    double gain;
    int a, b;
    bool operator<(const Candidate& o) const { return gain != o.gain ? gain < o.gain : std::tie(a, b) > std::tie(o.a, o.b); }
  };
  std::priority_queue<Candidate> edges;
  const auto gain_of = [&](int a, int b) {
    const auto [f1, c] = surface.face_with(a, b);
    const auto [f2, d] = surface.face_with(b, a);
    if (f1 < 0 || f2 < 0 || c == d) return 0.0;
    return flip_gain(criterion, surface.point(a), surface.point(b), surface.point(c), surface.point(d), min_gain);
  };
  for (const auto& [a, b] : first) edges.push({gain_of(a, b), a, b});
  // Area flips always lower the area; Delaunay flips on a curved surface
  // have no such potential, so a budget guarantees the end.
  std::size_t flips = 0, budget = 4 * surface.face_slots();
  while (!edges.empty() && budget-- > 0) {
    const Candidate top = edges.top();
    edges.pop();
    const int a = top.a, b = top.b;
    const auto [f1, c] = surface.face_with(a, b);
    const auto [f2, d] = surface.face_with(b, a);
    if (f1 < 0 || f2 < 0 || c == d || surface.has_edge(c, d) || is_fixed(f1) || is_fixed(f2)) continue;
    if (!(gain_of(a, b) > 0)) continue;
    const Triangle g1{a, d, c}, g2{d, b, c};
    if (!cells || !cells->toggles(a, b, c, d)) {
      if (CGAL::orientation(surface.exact(a), surface.exact(b), surface.exact(c), surface.exact(d)) == CGAL::COPLANAR)
        continue;
      if (surface.point_in_tetrahedron(a, b, c, d) || surface.meets_surface({g1, g2}, {f1, f2})) continue;
      if (cells) cells->add_foreign(surface.box({a, b, c, d}));
    }
    surface.remove_face(f1);
    surface.remove_face(f2);
    surface.add_face(g1);
    surface.add_face(g2);
    ++flips;
    for (const auto& [u, v] : {std::pair{a, d}, std::pair{d, b}, std::pair{b, c}, std::pair{c, a}}) {
      const double g = gain_of(std::min(u, v), std::max(u, v));
      if (g > 0) edges.push({g, std::min(u, v), std::max(u, v)});
    }
  }
  return flips;
}

// The flip pass of flip_delaunay_cells, on the kept flags alone (the
// complex never changes, so a cell that held an edge once always does).
class CellToggles {
 public:
  CellToggles(const DelaunayComplex<3>& dt, std::vector<char>& kept, std::vector<Triangle> fixed)
      : dt_(dt), kept_(kept), fixed_(std::move(fixed)) {}

  // Rounds: a flip can also free an edge whose faces it did not touch (by
  // taking (c, d) off the boundary, or a face off the boundary next to the
  // edge's cell), so every boundary edge is looked at again until a round
  // makes no flip; the budget (pops, over all rounds) bounds the whole.
  std::size_t run() {
    std::size_t flips = 0, budget = 4 * scan();
    while (!queue_.empty() && budget > 0) {
      std::size_t round = 0;
      while (!queue_.empty() && budget > 0) {
        --budget;
        const Candidate top = queue_.top();
        queue_.pop();
        const auto flip = flip_at(top.cell, top.a, top.b);
        if (!flip || !(gain_if_allowed(*flip) > 0)) continue;
        const int t = flip->cell;
        kept_[static_cast<std::size_t>(t)] = !kept_[static_cast<std::size_t>(t)];
        ++round;
        for (const auto& [u, v] : {std::pair{flip->a, flip->d}, std::pair{flip->d, flip->b},
                                   std::pair{flip->b, flip->c}, std::pair{flip->c, flip->a}})
          consider(t, std::min(u, v), std::max(u, v));
      }
      flips += round;
      ++rounds_;
      if (round == 0) break;
      scan();
    }
    return flips;
  }
  std::size_t rounds() const { return rounds_; }

 private:
  // Faces (a, b, c) and (b, a, d), counter-clockwise from outside, and the
  // cell (a, b, c, d) whose toggling flips (a, b) to (c, d).
  struct Flip {
    int cell, a, b, c, d;
  };
  struct Candidate {
    double gain;
    int a, b, cell;  // cell: one holding the edge (a, b)
    bool operator<(const Candidate& o) const { return gain != o.gain ? gain < o.gain : std::tie(a, b) > std::tie(o.a, o.b); }
  };

  int cells() const { return static_cast<int>(dt_.cells.rows()); }
  bool inside(int c) const { return c >= 0 && kept_[static_cast<std::size_t>(c)]; }

  // Queues every boundary edge worth a flip; returns the boundary faces.
  std::size_t scan() {
    std::size_t faces = 0;
    for (int c = 0; c < cells(); ++c) {
      if (!inside(c)) continue;
      for (int i = 0; i < 4; ++i) {
        if (inside(dt_.neighbors(c, i))) continue;
        ++faces;
        for (int k = 0; k < 3; ++k) {  // each edge once: from the face holding it as (low, high)
          const int p = dt_.cells(c, kFace3[i][k]), q = dt_.cells(c, kFace3[i][(k + 1) % 3]);
          if (p < q) consider(c, p, q);
        }
      }
    }
    return faces;
  }
  int local(int c, int v) const {
    int k = 0;
    while (dt_.cells(c, k) != v) ++k;
    return k;
  }
  Eigen::Vector3d point(int v) const { return dt_.points.row(v).transpose(); }

  // The two faces of cell c holding its edge (u, v): opposite its other
  // two vertices, given as local indices.
  void off_edge(int c, int u, int v, int (&k)[2]) const {
    int n = 0;
    for (int i = 0; i < 4; ++i)
      if (dt_.cells(c, i) != u && dt_.cells(c, i) != v) k[n++] = i;
  }
  bool boundary_face(int c, int i) const { return inside(c) != inside(dt_.neighbors(c, i)); }

  // The flip at the edge (u, v), from a cell c holding it with a boundary
  // face at it (else none: whatever took that face away re-considers the
  // edge from a cell that has one). The flip's cell holds both boundary
  // faces at the edge, so it is c or its neighbour across that face, and
  // its faces off the edge are not on the boundary.
  std::optional<Flip> flip_at(int c, int u, int v) const {
    int k[2];
    off_edge(c, u, v, k);
    const bool b0 = boundary_face(c, k[0]), b1 = boundary_face(c, k[1]);
    int t = -1;
    if (b0 && b1) {
      t = c;
    } else if (b0 || b1) {
      const int y = dt_.neighbors(c, b0 ? k[0] : k[1]);
      if (y < 0) return std::nullopt;
      int l[2];
      off_edge(y, u, v, l);
      if (boundary_face(y, l[0]) && boundary_face(y, l[1])) t = y;
    }
    if (t < 0) return std::nullopt;
    off_edge(t, u, v, k);
    const bool side = inside(t);
    if (boundary_face(t, local(t, u)) || boundary_face(t, local(t, v))) return std::nullopt;
    // Orient: the face opposite d is counter-clockwise seen from outside
    // the cell (kFace3), so from outside the solid when the cell is kept.
    const int c3 = dt_.cells(t, k[0]), d3 = dt_.cells(t, k[1]);
    const int* f = kFace3[k[1]];
    int tri[3] = {dt_.cells(t, f[0]), dt_.cells(t, f[1]), dt_.cells(t, f[2])};
    if (!side) std::swap(tri[1], tri[2]);
    int j = 0;
    while (tri[(j + 2) % 3] != c3) ++j;  // the edge's ends in face order: (a, b, c3)
    return Flip{t, tri[j], tri[(j + 1) % 3], c3, d3};
  }

  // Whether a boundary face holds the edge (u, v) of cell c: a walk around
  // the edge (as constriction's §5.3 test), both ways when the ring is open.
  bool edge_on_boundary(int c, int u, int v) const {
    int others[2];
    off_edge(c, u, v, others);
    others[0] = dt_.cells(c, others[0]);
    others[1] = dt_.cells(c, others[1]);
    for (int direction = 0; direction < 2; ++direction) {
      int x = c, cross = others[direction], stay = others[1 - direction];
      for (;;) {
        const int y = dt_.neighbors(x, local(x, cross));
        if (inside(x) != inside(y)) return true;
        if (y < 0) break;
        if (y == c) return false;
        int fresh = 0;
        for (int i = 0; i < 4; ++i) {
          const int g = dt_.cells(y, i);
          if (g != u && g != v && g != stay) fresh = g;
        }
        x = y;
        cross = stay;
        stay = fresh;
      }
    }
    return false;
  }

  // A flip worth making and allowed: (c, d) not on the boundary yet (it
  // would meet four boundary faces), neither face kept (§5.7).
  double gain_if_allowed(const Flip& f) const {
    const double g =
        flip_gain(FlipCriterion::area_then_delaunay, point(f.a), point(f.b), point(f.c), point(f.d), 0.0);
    if (!(g > 0) || is_fixed(f.a, f.b, f.c) || is_fixed(f.b, f.a, f.d) || edge_on_boundary(f.cell, f.c, f.d)) return 0.0;
    return g;
  }

  bool is_fixed(int a, int b, int c) const {
    if (fixed_.empty()) return false;
    Triangle t{a, b, c};
    std::sort(t.begin(), t.end());
    return std::binary_search(fixed_.begin(), fixed_.end(), t);
  }

  void consider(int c, int u, int v) {
    const auto flip = flip_at(c, u, v);
    if (!flip) return;
    const double g = gain_if_allowed(*flip);
    if (g > 0) queue_.push({g, std::min(u, v), std::max(u, v), flip->cell});
  }

  const DelaunayComplex<3>& dt_;
  std::vector<char>& kept_;
  std::vector<Triangle> fixed_;
  std::priority_queue<Candidate> queue_;
  std::size_t rounds_ = 0;
};

}  // namespace

std::size_t flip_delaunay_cells(const DelaunayComplex<3>& complex, std::vector<char>& kept, const Eigen::MatrixXi& keep) {
  return CellToggles(complex, kept, sorted_triangles(keep)).run();
}

std::size_t flip_boundary(const Eigen::MatrixX3d& points, Eigen::MatrixX3i& boundary, FlipCriterion criterion,
                          const Eigen::MatrixXi& keep, double min_gain, const DelaunayComplex<3>* cells,
                          std::optional<BoundarySurface>* kept_surface) {
  const bool delaunay = criterion == FlipCriterion::area_then_delaunay;
  const std::vector<std::pair<int, int>> by_area = candidate_edges(points, boundary, FlipCriterion::area, min_gain);
  if (by_area.empty() && (!delaunay || candidate_edges(points, boundary, criterion, min_gain).empty())) return 0;
  BoundarySurface surface(points, boundary);
  const std::vector<Triangle> fixed = sorted_triangles(keep);
  std::optional<CellFlips> cell_flips;
  if (cells) {
    cell_flips.emplace(*cells, surface_grid(points));
    cell_flips->add_foreign_faces(surface);
  }
  CellFlips* untested = cell_flips ? &*cell_flips : nullptr;
  std::size_t flips = flip_pass(surface, by_area, FlipCriterion::area, fixed, min_gain, untested);
  if (delaunay) {
    // The Delaunay candidates of the surface the area flips left.
    const Eigen::MatrixX3i after = surface.boundary();
    flips += flip_pass(surface, candidate_edges(points, after, criterion, min_gain), criterion, fixed, min_gain, untested);
  }
  boundary = surface.boundary();
  if (kept_surface) kept_surface->emplace(std::move(surface));
  return flips;
}

}  // namespace scanstation
