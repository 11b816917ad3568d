#include "reconstruct/augmentation.h"

#include "reconstruct/gamma_indicator.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/intersections.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <queue>
#include <unordered_map>

namespace scanstation {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Triangle = std::array<int, 3>;

// Uniform grid over axis-aligned boxes, for "which points / triangles are
// near this tetrahedron". Ids may be reported more than once. Boxes spanning
// many cells (the long triangles of a locked boundary) go to a list that
// every query visits, and so does a query over many cells.
class Grid {
 public:
  Grid(const Eigen::AlignedBox3d& bounds, double cell) : origin_(bounds.min()), cell_(cell) {}

  void insert(int id, const Eigen::AlignedBox3d& box) {
    if (cells(box) > kMaxCells) {
      large_.push_back(id);
      return;
    }
    for_cells(box, [&](std::uint64_t k) { cells_[k].push_back(id); });
  }
  void erase(int id, const Eigen::AlignedBox3d& box) {
    if (cells(box) > kMaxCells) {
      large_.erase(std::remove(large_.begin(), large_.end(), id), large_.end());
      return;
    }
    for_cells(box, [&](std::uint64_t k) {
      auto& v = cells_[k];
      v.erase(std::remove(v.begin(), v.end(), id), v.end());
    });
  }
  /// Calls f(id) for (at least) every id whose box may meet `box`.
  template <typename F>
  void visit(const Eigen::AlignedBox3d& box, F&& f) const {
    for (const int id : large_) f(id);
    if (cells(box) > kMaxCells) {
      for (const auto& [key, ids] : cells_)
        for (const int id : ids) f(id);
      return;
    }
    for_cells(box, [&](std::uint64_t k) {
      if (const auto it = cells_.find(k); it != cells_.end())
        for (const int id : it->second) f(id);
    });
  }

 private:
  static constexpr double kMaxCells = 512;
  Eigen::Array3i index(const Eigen::Vector3d& x) const { return ((x - origin_) / cell_).array().floor().cast<int>(); }
  double cells(const Eigen::AlignedBox3d& box) const {
    const Eigen::Array3d span = ((box.max() - box.min()) / cell_).array().floor() + 1.0;
    return span.prod();
  }
  template <typename F>
  void for_cells(const Eigen::AlignedBox3d& box, F&& f) const {
    const Eigen::Array3i lo = index(box.min()), hi = index(box.max());
    for (int x = lo.x(); x <= hi.x(); ++x)
      for (int y = lo.y(); y <= hi.y(); ++y)
        for (int z = lo.z(); z <= hi.z(); ++z)
          f((static_cast<std::uint64_t>(x & 0x1FFFFF) << 42) | (static_cast<std::uint64_t>(y & 0x1FFFFF) << 21) |
            static_cast<std::uint64_t>(z & 0x1FFFFF));
  }
  Eigen::Vector3d origin_;
  double cell_;
  std::unordered_map<std::uint64_t, std::vector<int>> cells_;
  std::vector<int> large_;
};

struct Carve {
  double key;
  int face;
  int vertex;
  bool operator<(const Carve& o) const {
    if (key != o.key) return key > o.key;
    return face != o.face ? face > o.face : vertex > o.vertex;
  }
};

class Augmenter {
 public:
  Augmenter(const Eigen::MatrixX3d& P, const std::vector<std::vector<int>>& adjacency, const Eigen::MatrixX3i& boundary)
      : P_(P),
        adjacency_(adjacency),
        points_(bounds(P), cell_size(P)),
        faces_grid_(bounds(P), cell_size(P)),
        faces_at_(static_cast<std::size_t>(P.rows())),
        on_boundary_(static_cast<std::size_t>(P.rows()), 0) {
    for (Eigen::Index i = 0; i < P.rows(); ++i) {
      cgal_.emplace_back(P(i, 0), P(i, 1), P(i, 2));
      points_.insert(static_cast<int>(i), Eigen::AlignedBox3d(P.row(i).transpose(), P.row(i).transpose()));
    }
    for (Eigen::Index f = 0; f < boundary.rows(); ++f) add_face({boundary(f, 0), boundary(f, 1), boundary(f, 2)});
  }

  Augmentation run(std::vector<int>& interior, const AugmentationOptions& options) {
    Augmentation result;
    for (Eigen::Index k = 0; k < options.keep.rows(); ++k) {
      Triangle t{options.keep(k, 0), options.keep(k, 1), options.keep(k, 2)};
      std::sort(t.begin(), t.end());
      keep_.push_back(t);
    }
    std::sort(keep_.begin(), keep_.end());
    for (double c0 = options.highest; c0 >= options.lowest - 1e-9 && !interior.empty(); c0 -= options.step) {
      c0 = std::max(c0, options.lowest);
      heap_ = {};
      for (const int v : interior) propose(v, c0);
      while (!heap_.empty()) {
        const Carve top = heap_.top();
        heap_.pop();
        if (!alive_[static_cast<std::size_t>(top.face)] || on_boundary_[static_cast<std::size_t>(top.vertex)]) continue;
        if (!allowed(top.face, top.vertex, c0)) continue;
        carve(top.face, top.vertex);
        ++result.carved;
        result.c0_used = c0;
        for (const int v : near(top.vertex))
          if (!on_boundary_[static_cast<std::size_t>(v)]) propose(v, c0);
      }
      interior.erase(std::remove_if(interior.begin(), interior.end(),
                                    [&](int v) { return on_boundary_[static_cast<std::size_t>(v)] != 0; }),
                     interior.end());
      if (interior.empty()) break;
      result.c0_used = c0;
    }
    return result;
  }

  Eigen::MatrixX3i boundary() const {
    std::vector<Triangle> live;
    for (std::size_t f = 0; f < faces_.size(); ++f)
      if (alive_[f]) live.push_back(faces_[f]);
    Eigen::MatrixX3i out(static_cast<Eigen::Index>(live.size()), 3);
    for (std::size_t f = 0; f < live.size(); ++f) out.row(static_cast<Eigen::Index>(f)) << live[f][0], live[f][1], live[f][2];
    return out;
  }

 private:
  static Eigen::AlignedBox3d bounds(const Eigen::MatrixX3d& P) {
    return Eigen::AlignedBox3d(P.colwise().minCoeff().transpose(), P.colwise().maxCoeff().transpose());
  }
  // About two points per grid cell on a surface-like cloud.
  static double cell_size(const Eigen::MatrixX3d& P) {
    const Eigen::Vector3d extent = (P.colwise().maxCoeff() - P.colwise().minCoeff()).transpose();
    const double area = 2.0 * (extent.x() * extent.y() + extent.y() * extent.z() + extent.z() * extent.x());
    return std::max(std::sqrt(2.0 * area / static_cast<double>(std::max<Eigen::Index>(P.rows(), 1))), 1e-300);
  }
  Eigen::Vector3d p(int i) const { return P_.row(i).transpose(); }
  Eigen::AlignedBox3d box(std::initializer_list<int> ids) const {
    Eigen::AlignedBox3d b;
    for (const int i : ids) b.extend(p(i));
    return b;
  }

  void add_face(const Triangle& t) {
    const int id = static_cast<int>(faces_.size());
    faces_.push_back(t);
    alive_.push_back(1);
    for (const int v : t) {
      faces_at_[static_cast<std::size_t>(v)].push_back(id);
      on_boundary_[static_cast<std::size_t>(v)] = 1;
    }
    faces_grid_.insert(id, box({t[0], t[1], t[2]}));
  }
  void remove_face(int id) {
    alive_[static_cast<std::size_t>(id)] = 0;
    const Triangle& t = faces_[static_cast<std::size_t>(id)];
    faces_grid_.erase(id, box({t[0], t[1], t[2]}));
  }

  // Points within two Delaunay edges of v.
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

  void propose(int v, double c0) {
    for (const int u : near(v)) {
      if (!on_boundary_[static_cast<std::size_t>(u)]) continue;
      for (const int f : faces_at_[static_cast<std::size_t>(u)]) {
        if (!alive_[static_cast<std::size_t>(f)]) continue;
        const Triangle& t = faces_[static_cast<std::size_t>(f)];
        if (CGAL::orientation(cgal_[t[0]], cgal_[t[1]], cgal_[t[2]], cgal_[v]) != CGAL::NEGATIVE) continue;
        if (!allowed(f, v, c0)) continue;
        heap_.push({gamma_indicator(p(t[0]), p(t[1]), p(t[2]), p(v)), f, v});
      }
    }
  }

  // The triangle (a, b, c) is in γ([-1,1],[c0,1]) when no point lies in its
  // open symmetric lens N_γ(c0,c0): two balls of radius r/(1−|c0|) through
  // its circumcircle, centres on either side (Definition 3.1, Lemma 3.3).
  bool in_gamma(int a, int b, int c, double c0) const {
    const Eigen::Vector3d A = p(a), e1 = p(b) - A, e2 = p(c) - A, n = e1.cross(e2);
    const double nn = n.squaredNorm();
    if (!(nn > 0)) return false;
    const Eigen::Vector3d O = A + (e1.squaredNorm() * e2.cross(n) + e2.squaredNorm() * n.cross(e1)) / (2.0 * nn);
    const double r = (A - O).norm();
    const double rho = c0 <= -1.0 ? std::numeric_limits<double>::infinity() : r / (1.0 - std::abs(c0));
    const double d = std::isfinite(rho) ? std::sqrt(std::max(rho * rho - r * r, 0.0)) : 0.0;
    const Eigen::Vector3d unit = n / std::sqrt(nn);
    bool empty = true;
    points_.visit(Eigen::AlignedBox3d(O.array() - r, O.array() + r), [&](int q) {
      if (!empty || q == a || q == b || q == c) return;
      if (std::isfinite(rho)) {
        if ((p(q) - (O + d * unit)).norm() < rho && (p(q) - (O - d * unit)).norm() < rho) empty = false;
      } else if (CGAL::orientation(cgal_[a], cgal_[b], cgal_[c], cgal_[q]) == CGAL::COPLANAR &&
                 Kernel::Triangle_3(cgal_[a], cgal_[b], cgal_[c]).has_on(cgal_[q])) {
        empty = false;  // c0 = −1: the lens is the open triangle
      }
    });
    return empty;
  }

  // Exact: do two triangles meet anywhere but in the vertices/edges they share?
  bool improper(const Triangle& s, const Triangle& t) const {
    std::array<int, 3> shared{};
    int n = 0;
    for (const int a : s)
      if (std::find(t.begin(), t.end(), a) != t.end()) shared[static_cast<std::size_t>(n++)] = a;
    const auto tri = [&](const Triangle& x) { return Kernel::Triangle_3(cgal_[x[0]], cgal_[x[1]], cgal_[x[2]]); };
    const auto other = [&](const Triangle& x, int k) {  // the vertices of x not shared, in order
      std::array<int, 3> rest{};
      int m = 0;
      for (const int a : x)
        if (std::find(shared.begin(), shared.begin() + n, a) == shared.begin() + n) rest[static_cast<std::size_t>(m++)] = a;
      return rest[static_cast<std::size_t>(k)];
    };
    if (n == 3) return true;
    if (n == 0) return CGAL::do_intersect(tri(s), tri(t));
    if (n == 1) {
      const Kernel::Segment_3 es(cgal_[other(s, 0)], cgal_[other(s, 1)]), et(cgal_[other(t, 0)], cgal_[other(t, 1)]);
      return CGAL::do_intersect(es, tri(t)) || CGAL::do_intersect(et, tri(s));
    }
    const Point &a = cgal_[shared[0]], &b = cgal_[shared[1]], &x = cgal_[other(s, 0)], &y = cgal_[other(t, 0)];
    return CGAL::orientation(a, b, x, y) == CGAL::COPLANAR && CGAL::coplanar_orientation(a, b, x, y) == CGAL::POSITIVE;
  }

  bool allowed(int f, int v, double c0) const {
    const Triangle& t = faces_[static_cast<std::size_t>(f)];
    const int a = t[0], b = t[1], c = t[2];
    Triangle sorted = t;
    std::sort(sorted.begin(), sorted.end());
    if (std::binary_search(keep_.begin(), keep_.end(), sorted)) return false;
    const std::array<Triangle, 3> fresh{{{a, b, v}, {b, c, v}, {c, a, v}}};
    for (const Triangle& n : fresh)
      if (!in_gamma(n[0], n[1], n[2], c0)) return false;
    const Eigen::AlignedBox3d region = box({a, b, c, v});
    bool ok = true;
    // No other point in the closed tetrahedron: it would fall outside.
    const Kernel::Tetrahedron_3 tetra(cgal_[a], cgal_[b], cgal_[c], cgal_[v]);
    points_.visit(region, [&](int q) {
      if (ok && q != a && q != b && q != c && q != v && !tetra.has_on_unbounded_side(cgal_[q])) ok = false;
    });
    if (!ok) return false;
    faces_grid_.visit(region, [&](int g) {
      if (!ok || g == f || !alive_[static_cast<std::size_t>(g)]) return;
      for (const Triangle& n : fresh)
        if (improper(n, faces_[static_cast<std::size_t>(g)])) ok = false;
    });
    return ok;
  }

  void carve(int f, int v) {
    const Triangle t = faces_[static_cast<std::size_t>(f)];
    remove_face(f);
    add_face({t[0], t[1], v});
    add_face({t[1], t[2], v});
    add_face({t[2], t[0], v});
  }

  const Eigen::MatrixX3d& P_;
  const std::vector<std::vector<int>>& adjacency_;
  std::vector<Point> cgal_;
  Grid points_;
  Grid faces_grid_;
  std::vector<Triangle> faces_;
  std::vector<char> alive_;
  std::vector<std::vector<int>> faces_at_;
  std::vector<char> on_boundary_;
  std::priority_queue<Carve> heap_;
  std::vector<Triangle> keep_;  // sorted triples
};

}  // namespace

Augmentation augment_constriction(const Eigen::MatrixX3d& points, const std::vector<std::vector<int>>& adjacency,
                                  Eigen::MatrixX3i& boundary, std::vector<int>& interior_vertices,
                                  const AugmentationOptions& options) {
  if (interior_vertices.empty()) return {};
  Augmenter augmenter(points, adjacency, boundary);
  const Augmentation result = augmenter.run(interior_vertices, options);
  boundary = augmenter.boundary();
  return result;
}

}  // namespace scanstation
