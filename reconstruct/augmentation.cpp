#include "reconstruct/augmentation.h"

#include "reconstruct/boundary_surface.h"
#include "reconstruct/gamma_indicator.h"
#include "reconstruct/triangle_set.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <queue>
#include <unordered_map>

namespace scanstation {

template <typename Cells>
PointNeighbours::PointNeighbours(const Cells& cells, std::optional<CellsAround> own, const CellsAround* shared)
    : vertices_(cells.data()),
      cell_step_(Cells::IsRowMajor ? cells.outerStride() : 1),
      vertex_step_(Cells::IsRowMajor ? 1 : cells.outerStride()),
      per_cell_(static_cast<int>(cells.cols())),
      own_around_(std::move(own)),
      cells_around_(shared ? shared : &*own_around_),
      seen_(cells_around_->start.size() - 1, 0) {}

PointNeighbours::PointNeighbours(const DelaunayComplex<2>& dt) : PointNeighbours(dt.cells, CellsAround(dt), nullptr) {}
PointNeighbours::PointNeighbours(const DelaunayComplex<3>& dt) : PointNeighbours(dt.cells, CellsAround(dt), nullptr) {}
PointNeighbours::PointNeighbours(const DelaunayComplex<3>& dt, std::optional<CellsAround>& around)
    : PointNeighbours(dt.cells, std::nullopt, around ? &*around : &around.emplace(dt)) {}

std::span<const int> PointNeighbours::operator[](std::size_t v) const {
  auto [it, fresh] = lists_.try_emplace(v);
  if (fresh) {
    // Each once, in the order of the cells around v (a stamp per point
    // instead of sorting the ~7 copies of every neighbour).
    seen_[v] = v + 1;
    for (const int c : (*cells_around_)[v]) {
      const int* cell = vertices_ + c * cell_step_;
      for (int i = 0; i < per_cell_; ++i) {
        const auto u = static_cast<std::size_t>(cell[i * vertex_step_]);
        if (seen_[u] == v + 1) continue;
        seen_[u] = v + 1;
        it->second.push_back(static_cast<int>(u));
      }
    }
  }
  return it->second;
}

namespace {

using Triangle = BoundarySurface::Triangle;

struct Carve {
  double key;
  int face;
  int vertex;
  bool operator<(const Carve& o) const {
    if (key != o.key) return key > o.key;
    return face != o.face ? face > o.face : vertex > o.vertex;
  }
};

// The levels of c0 tried, from `highest` down to `lowest`. Each is computed
// from its step count rather than accumulated, so the last one is `lowest`
// itself: ten subtractions of 0.1 from −0.1 end at −0.9999999999999999,
// whose lens is not yet the degenerate one of c0 = −1.
std::vector<double> levels(const AugmentationOptions& options) {
  std::vector<double> out;
  for (int k = 0;; ++k) {
    out.push_back(std::max(options.highest - k * options.step, options.lowest));
    if (out.back() <= options.lowest || !(options.step > 0)) return out;
  }
}

// The offset d of the symmetric lens N_γ(c0,c0) of a simplex with
// circumradius r: its two balls of radius ρ = r/(1−|c0|) are centred at
// ±d·n from the circumcentre, d = √(ρ² − r²) (Definition 3.1).
double lens_offset(double r, double c0) {
  const double rho = r / (1.0 - std::abs(c0));
  return std::sqrt(std::max(rho * rho - r * r, 0.0));
}

// What a popped candidate gets: carved now, tried again at the next (lower)
// level, or dropped for good (a point lies in its tetrahedron: points never
// move, so no level changes that).
enum class Verdict { carve, retry, drop };

// The adaptive levels of §5.4, shared by 2D and 3D: at each c0 from
// `highest` down to `lowest`, every candidate carve of the points still
// inside, smallest γ-indicator first, checked in full when it is popped.
// What failed at one level waits for the next instead of being proposed
// again from scratch: only the faces made since a point's last proposal are
// new to it (start_level).
template <typename Carver>
Augmentation run_levels(Carver& carver, std::priority_queue<Carve>& heap, std::vector<int>& interior,
                        const AugmentationOptions& options) {
  Augmentation result;
  std::vector<Carve> waiting;
  for (const double c0 : levels(options)) {
    if (interior.empty()) break;
    heap = {};
    for (const Carve& c : waiting)
      if (carver.still_there(c)) heap.push(c);
    waiting.clear();
    carver.start_level(interior);
    while (!heap.empty()) {
      const Carve top = heap.top();
      heap.pop();
      if (!carver.still_there(top)) continue;
      const Verdict verdict = carver.verdict(top.face, top.vertex, c0);
      if (verdict == Verdict::retry) waiting.push_back(top);
      if (verdict != Verdict::carve) continue;
      carver.carve(top.face, top.vertex);
      ++result.carved;
      carver.propose_around(top.vertex);
    }
    interior.erase(std::remove_if(interior.begin(), interior.end(), [&](int v) { return carver.on_boundary(v); }),
                   interior.end());
    result.c0_used = c0;
  }
  return result;
}

class Augmenter {
 public:
  Augmenter(const Eigen::MatrixX3d& P, const PointNeighbours& adjacency, const Eigen::MatrixX3i& boundary,
            const Eigen::MatrixXi& keep, std::shared_ptr<const PointTree> tree)
      : adjacency_(adjacency), surface_(P, boundary, std::move(tree)), keep_(keep), proposed_below_(static_cast<std::size_t>(P.rows()), 0) {}

  Augmentation run(std::vector<int>& interior, const AugmentationOptions& options) {
    return run_levels(*this, heap_, interior, options);
  }

  // The hooks run_levels drives.
  void start_level(const std::vector<int>& interior) {
    for (const int v : interior) propose(v);
  }
  bool on_boundary(int v) const { return surface_.on_boundary(v); }
  bool still_there(const Carve& c) const { return surface_.alive(c.face) && !surface_.on_boundary(c.vertex); }
  void propose_around(int v) {
    for (const int u : near(v))
      if (!surface_.on_boundary(u)) propose(u);
  }

  Eigen::MatrixX3i boundary() const { return surface_.boundary(); }
  BoundarySurface&& release_surface() { return std::move(surface_); }

  template <typename Carver>
  friend Augmentation run_levels(Carver&, std::priority_queue<Carve>&, std::vector<int>&, const AugmentationOptions&);

 private:
  // Points within two Delaunay edges of v: those whose candidates a carve
  // at v may have changed.
  std::vector<int> near(int v) const {
    std::vector<int> out;
    for (const int u : adjacency_[static_cast<std::size_t>(v)]) {
      out.push_back(u);
      for (const int w : adjacency_[static_cast<std::size_t>(u)]) out.push_back(w);
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }

  // Face ids are never reused and a candidate's key depends only on its face
  // and point, so a point proposed again (after a carve nearby, or at the
  // next level) only needs the faces made since its last proposal: the
  // older ones were carved, dropped, or wait in run_levels.
  void propose(int v) {
    const int seen = proposed_below_[static_cast<std::size_t>(v)];
    proposed_below_[static_cast<std::size_t>(v)] = static_cast<int>(surface_.face_slots());
    // The boundary triangles with a corner next to v, each once. Corners two
    // Delaunay edges away were never needed: without them every point of
    // CGAL's meshes still comes on, with the same recall (some at a lower
    // level). They made ten times the candidates on densely scanned flat
    // faces, where Delaunay neighbours reach across the face, and each
    // candidate's lens is searched through hundreds of points.
    std::vector<int> faces;
    for (const int u : adjacency_[static_cast<std::size_t>(v)]) {
      if (!surface_.on_boundary(u)) continue;
      for (const int f : surface_.faces_at(u))
        if (f >= seen) faces.push_back(f);
    }
    std::sort(faces.begin(), faces.end());
    faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
    for (const int f : faces) {
      const Triangle& t = surface_.face(f);
      // v must lie strictly behind the face, inside the solid.
      if (CGAL::orientation(surface_.exact(t[0]), surface_.exact(t[1]), surface_.exact(t[2]), surface_.exact(v)) !=
          CGAL::NEGATIVE)
        continue;
      // The costly tests wait until the candidate reaches the top of the
      // heap: most candidates of a point are never looked at again once
      // a cheaper one has brought it to the boundary.
      heap_.push({gamma_indicator(surface_.point(t[0]), surface_.point(t[1]), surface_.point(t[2]), surface_.point(v)),
                  f, v});
    }
  }

  // The triangle (a, b, c) is in γ([-1,1],[c0,1]) when no point lies in its
  // open symmetric lens N_γ(c0,c0): two balls of radius ρ = r/(1−|c0|)
  // through its circumcircle, centres at ±d·n with d = √(ρ² − r²)
  // (Definition 3.1, Lemma 3.3). A point at height h above the circumcircle's
  // plane and s = r² − |q − O|² is in the lens iff s > 2|h|·d, so it blocks
  // the triangle exactly for d < s/(2|h|): the lens shrinks as c0 falls, and
  // each triangle has one threshold d*, allowed iff d ≥ d*. What a search
  // learns of d* (a lower bound, or d* itself) is kept for all levels.
  bool in_gamma(int a, int b, int c, double c0) const {
    const Eigen::Vector3d A = surface_.point(a), e1 = surface_.point(b) - A, e2 = surface_.point(c) - A,
                          n = e1.cross(e2);
    const double nn = n.squaredNorm();
    if (!(nn > 0)) return false;
    const Eigen::Vector3d O = A + (e1.squaredNorm() * e2.cross(n) + e2.squaredNorm() * n.cross(e1)) / (2.0 * nn);
    const double r = (A - O).norm();
    if (c0 <= -1.0) {  // the lens degenerates to the open triangle
      return surface_.points_in_ball(O, r, [&](int q, const Eigen::Vector3d&) {
        return q == a || q == b || q == c ||
               CGAL::orientation(surface_.exact(a), surface_.exact(b), surface_.exact(c), surface_.exact(q)) !=
                   CGAL::COPLANAR ||
               !BoundarySurface::Kernel::Triangle_3(surface_.exact(a), surface_.exact(b), surface_.exact(c))
                    .has_on(surface_.exact(q));
      });
    }
    const double d = lens_offset(r, c0);
    Triangle key{a, b, c};
    std::sort(key.begin(), key.end());
    LensThreshold& known = thresholds_[key];
    if (known.exact || d < known.at_least) return d >= known.at_least;
    // The search ends at the first point that blocks this level: the
    // triangle waits for a lower one, and the bound tells the levels up to
    // that point's threshold without a search. Nearly coplanar points (flat
    // faces scanned densely) put hundreds of points in a circumball, and
    // most candidates fail the first levels: a search to the deepest level
    // (then kept for all) cost more than stopping early and searching again
    // at the level where the bound runs out (augmentation on the 26 meshes
    // of README 26.8 → 21 ms, the same carves).
    const Eigen::Vector3d unit = n / std::sqrt(nn);
    double highest = known.at_least;
    const bool complete = surface_.points_in_ball(O, r, [&](int q, const Eigen::Vector3d& p) {
      if (q == a || q == b || q == c) return true;
      const Eigen::Vector3d x = p - O;
      const double s = r * r - x.squaredNorm(), h = std::abs(x.dot(unit));
      if (!(s > 0.0)) return true;  // outside the circumball: in no lens
      const double blocks_below = h > 0.0 ? s / (2.0 * h) : std::numeric_limits<double>::infinity();
      highest = std::max(highest, blocks_below);
      return !(blocks_below > d);
    });
    known.at_least = highest;
    known.exact = complete;
    return d >= highest;
  }

  Verdict verdict(int f, int v, double c0) const {
    const Triangle& t = surface_.face(f);
    if (keep_.contains(t)) return Verdict::drop;  // §5.7
    const std::vector<Triangle> fresh{{t[0], t[1], v}, {t[1], t[2], v}, {t[2], t[0], v}};
    for (const Triangle& n : fresh)
      if (!in_gamma(n[0], n[1], n[2], c0)) return Verdict::retry;
    // No point may fall outside, and the new triangles may not cross the
    // surface: the "simplices that cross a removed one" of §5.4.
    if (surface_.point_in_tetrahedron(t[0], t[1], t[2], v)) return Verdict::drop;
    return surface_.meets_surface(fresh, {f}) ? Verdict::retry : Verdict::carve;
  }

  void carve(int f, int v) {
    const Triangle t = surface_.face(f);
    surface_.remove_face(f);
    surface_.add_face({t[0], t[1], v});
    surface_.add_face({t[1], t[2], v});
    surface_.add_face({t[2], t[0], v});
  }

  // What is known of a triangle's lens threshold d* (see in_gamma).
  struct LensThreshold {
    double at_least = 0.0;  // d* ≥ this
    bool exact = false;     // d* = at_least
  };
  struct TriangleHash {
    std::size_t operator()(const Triangle& t) const {
      return std::hash<std::uint64_t>()((static_cast<std::uint64_t>(t[0]) * 0x9E3779B97F4A7C15ULL) ^
                                        (static_cast<std::uint64_t>(t[1]) << 21) ^ static_cast<std::uint64_t>(t[2]));
    }
  };

  const PointNeighbours& adjacency_;
  BoundarySurface surface_;
  std::priority_queue<Carve> heap_;
  TriangleSet keep_;
  mutable std::unordered_map<Triangle, LensThreshold, TriangleHash> thresholds_;
  std::vector<int> proposed_below_;  // per point: faces below this id were proposed already
};

}  // namespace

Augmentation augment_constriction(const Eigen::MatrixX3d& points, const PointNeighbours& adjacency,
                                  Eigen::MatrixX3i& boundary, std::vector<int>& interior_vertices,
                                  const AugmentationOptions& options, std::optional<BoundarySurface>* surface,
                                  std::shared_ptr<const PointTree> tree) {
  if (interior_vertices.empty()) return {};
  Augmenter augmenter(points, adjacency, boundary, options.keep, std::move(tree));
  const Augmentation result = augmenter.run(interior_vertices, options);
  boundary = augmenter.boundary();
  if (surface) surface->emplace(augmenter.release_surface());
  return result;
}

}  // namespace scanstation

namespace scanstation {

namespace {

using Kernel2 = CGAL::Exact_predicates_inexact_constructions_kernel;

// The polygon as a linked cycle with a grid over its edges (edge = its start
// vertex a, running to next[a]).
class Augmenter2 {
 public:
  Augmenter2(const Eigen::MatrixX2d& P, const PointNeighbours& adjacency, const Eigen::MatrixX2i& boundary)
      : P_(P),
        adjacency_(adjacency),
        next_(static_cast<std::size_t>(P.rows()), -1),
        points_(bounds(P), cell(P)),
        edges_(bounds(P), cell(P)) {
    for (Eigen::Index i = 0; i < P.rows(); ++i) {
      exact_.emplace_back(P(i, 0), P(i, 1));
      points_.insert(static_cast<int>(i), Eigen::AlignedBox3d(at(static_cast<int>(i)), at(static_cast<int>(i))));
    }
    for (Eigen::Index e = 0; e < boundary.rows(); ++e) link(boundary(e, 0), boundary(e, 1));
  }

  Augmentation run(std::vector<int>& interior, const AugmentationOptions& options) {
    return run_levels(*this, heap_, interior, options);
  }

  // The hooks run_levels drives; an edge is named by its start vertex.
  // An edge keeps its name (start vertex) when its end changes, so 2D
  // proposes every point afresh at each level and never defers.
  void start_level(const std::vector<int>& interior) {
    for (const int v : interior) propose(v);
  }
  bool on_boundary(int v) const { return next_[static_cast<std::size_t>(v)] >= 0; }
  bool still_there(const Carve& c) const { return !on_boundary(c.vertex) && on_boundary(c.face); }
  void propose_around(int v) {
    for (const int u : adjacency_[static_cast<std::size_t>(v)])
      if (!on_boundary(u)) propose(u);
  }

  Eigen::MatrixX2i boundary() const {
    std::vector<std::array<int, 2>> e;
    for (std::size_t a = 0; a < next_.size(); ++a)
      if (next_[a] >= 0) e.push_back({static_cast<int>(a), next_[a]});
    Eigen::MatrixX2i out(static_cast<Eigen::Index>(e.size()), 2);
    for (std::size_t k = 0; k < e.size(); ++k) out.row(static_cast<Eigen::Index>(k)) << e[k][0], e[k][1];
    return out;
  }

  template <typename Carver>
  friend Augmentation run_levels(Carver&, std::priority_queue<Carve>&, std::vector<int>&, const AugmentationOptions&);

 private:
  static Eigen::AlignedBox3d bounds(const Eigen::MatrixX2d& P) {
    const Eigen::Vector2d lo = P.colwise().minCoeff().transpose(), hi = P.colwise().maxCoeff().transpose();
    return Eigen::AlignedBox3d(Eigen::Vector3d(lo.x(), lo.y(), 0), Eigen::Vector3d(hi.x(), hi.y(), 0));
  }
  static double cell(const Eigen::MatrixX2d& P) {
    const Eigen::Vector2d extent = (P.colwise().maxCoeff() - P.colwise().minCoeff()).transpose();
    return std::max(std::sqrt(2.0 * extent.x() * extent.y() / static_cast<double>(std::max<Eigen::Index>(P.rows(), 1))),
                    std::max(extent.maxCoeff(), 1e-300) / static_cast<double>(std::max<Eigen::Index>(P.rows(), 1)));
  }
  Eigen::Vector3d at(int i) const { return Eigen::Vector3d(P_(i, 0), P_(i, 1), 0.0); }
  Eigen::AlignedBox3d box(int a, int b) const {
    Eigen::AlignedBox3d x(at(a), at(a));
    x.extend(at(b));
    return x;
  }
  void link(int a, int b) {
    next_[static_cast<std::size_t>(a)] = b;
    edges_.insert(a, box(a, b));
  }
  void unlink(int a) {
    edges_.erase(a, box(a, next_[static_cast<std::size_t>(a)]));
    next_[static_cast<std::size_t>(a)] = -1;
  }

  void propose(int v) {
    std::vector<int> near;
    for (const int u : adjacency_[static_cast<std::size_t>(v)]) {
      near.push_back(u);
      for (const int w : adjacency_[static_cast<std::size_t>(u)]) near.push_back(w);
    }
    std::sort(near.begin(), near.end());
    near.erase(std::unique(near.begin(), near.end()), near.end());
    for (const int a : near) {
      const int b = next_[static_cast<std::size_t>(a)];
      if (b < 0 || CGAL::orientation(exact_[static_cast<std::size_t>(a)], exact_[static_cast<std::size_t>(b)],
                                     exact_[static_cast<std::size_t>(v)]) != CGAL::LEFT_TURN)
        continue;
      heap_.push({gamma_indicator(Eigen::Vector2d(P_.row(a)), Eigen::Vector2d(P_.row(b)), Eigen::Vector2d(P_.row(v))), a, v});
    }
  }

  // The edge (p, q) is in γ([-1,1],[c0,1]) when its open symmetric lens holds
  // no point (two discs of radius r/(1−|c0|) through p and q).
  bool in_gamma(int p, int q, double c0) const {
    const Eigen::Vector2d A = P_.row(p), B = P_.row(q), mid = 0.5 * (A + B), e = B - A;
    const double r = 0.5 * e.norm();
    const Eigen::Vector2d unit = Eigen::Vector2d(-e.y(), e.x()).normalized();
    const bool open_segment = c0 <= -1.0;
    const double rho = open_segment ? 0.0 : r / (1.0 - std::abs(c0));
    const double d = std::sqrt(std::max(rho * rho - r * r, 0.0));
    bool empty = true;
    points_.visit(Eigen::AlignedBox3d(Eigen::Vector3d(mid.x() - r, mid.y() - r, 0), Eigen::Vector3d(mid.x() + r, mid.y() + r, 0)),
                  [&](int x) {
                    if (!empty || x == p || x == q) return;
                    const Eigen::Vector2d X = P_.row(x);
                    if (!open_segment) {
                      if ((X - (mid + d * unit)).norm() < rho && (X - (mid - d * unit)).norm() < rho) empty = false;
                    } else if (Kernel2::Segment_2(exact_[static_cast<std::size_t>(p)], exact_[static_cast<std::size_t>(q)])
                                   .has_on(exact_[static_cast<std::size_t>(x)])) {
                      empty = false;
                    }
                  });
    return empty;
  }

  // Exact: do segments (p, q) and (s, t) meet anywhere but a shared endpoint?
  bool improper(int p, int q, int s, int t) const {
    const auto& X = exact_;
    const auto P = [&](int i) { return X[static_cast<std::size_t>(i)]; };
    const int shared = (p == s || p == t) ? p : (q == s || q == t) ? q : -1;
    if (shared < 0) return CGAL::do_intersect(Kernel2::Segment_2(P(p), P(q)), Kernel2::Segment_2(P(s), P(t)));
    const int x = shared == p ? q : p, y = shared == s ? t : s;
    if (x == y) return true;
    return CGAL::orientation(P(shared), P(x), P(y)) == CGAL::COLLINEAR && CGAL::angle(P(x), P(shared), P(y)) == CGAL::ACUTE;
  }

  Verdict verdict(int a, int v, double c0) const { return allowed(a, v, c0) ? Verdict::carve : Verdict::drop; }

  bool allowed(int a, int v, double c0) const {
    const int b = next_[static_cast<std::size_t>(a)];
    // v must lie strictly inside, on the left of a → b.
    if (CGAL::orientation(exact_[static_cast<std::size_t>(a)], exact_[static_cast<std::size_t>(b)],
                          exact_[static_cast<std::size_t>(v)]) != CGAL::LEFT_TURN)
      return false;
    if (!in_gamma(a, v, c0) || !in_gamma(v, b, c0)) return false;
    const auto& X = exact_;
    bool ok = true;
    Eigen::AlignedBox3d region = box(a, b);
    region.extend(at(v));
    const Kernel2::Triangle_2 triangle(X[static_cast<std::size_t>(a)], X[static_cast<std::size_t>(b)], X[static_cast<std::size_t>(v)]);
    points_.visit(region, [&](int q) {
      if (ok && q != a && q != b && q != v && !triangle.has_on_unbounded_side(X[static_cast<std::size_t>(q)])) ok = false;
    });
    if (!ok) return false;
    edges_.visit(region, [&](int s) {
      const int t = next_[static_cast<std::size_t>(s)];
      if (!ok || t < 0 || s == a) return;
      if (improper(a, v, s, t) || improper(v, b, s, t)) ok = false;
    });
    return ok;
  }

  void carve(int a, int v) {
    const int b = next_[static_cast<std::size_t>(a)];
    unlink(a);
    link(a, v);
    link(v, b);
  }

  const Eigen::MatrixX2d& P_;
  const PointNeighbours& adjacency_;
  std::vector<Kernel2::Point_2> exact_;
  std::vector<int> next_;
  BoxGrid points_;
  BoxGrid edges_;
  std::priority_queue<Carve> heap_;
};

}  // namespace

Augmentation augment_constriction(const Eigen::MatrixX2d& points, const PointNeighbours& adjacency,
                                  Eigen::MatrixX2i& boundary, std::vector<int>& interior_vertices,
                                  const AugmentationOptions& options) {
  if (interior_vertices.empty()) return {};
  Augmenter2 augmenter(points, adjacency, boundary);
  const Augmentation result = augmenter.run(interior_vertices, options);
  boundary = augmenter.boundary();
  return result;
}

}  // namespace scanstation
