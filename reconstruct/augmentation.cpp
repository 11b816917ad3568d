#include "reconstruct/augmentation.h"

#include "reconstruct/boundary_surface.h"
#include "reconstruct/gamma_indicator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

namespace scanstation {

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

class Augmenter {
 public:
  Augmenter(const Eigen::MatrixX3d& P, const std::vector<std::vector<int>>& adjacency, const Eigen::MatrixX3i& boundary,
            const Eigen::MatrixXi& keep)
      : adjacency_(adjacency), surface_(P, boundary) {
    for (Eigen::Index k = 0; k < keep.rows(); ++k) {
      Triangle t{keep(k, 0), keep(k, 1), keep(k, 2)};
      std::sort(t.begin(), t.end());
      keep_.push_back(t);
    }
    std::sort(keep_.begin(), keep_.end());
  }

  Augmentation run(std::vector<int>& interior, const AugmentationOptions& options) {
    Augmentation result;
    for (double c0 = options.highest; c0 >= options.lowest - 1e-9 && !interior.empty(); c0 -= options.step) {
      c0 = std::max(c0, options.lowest);
      heap_ = {};
      for (const int v : interior) propose(v, c0);
      while (!heap_.empty()) {
        const Carve top = heap_.top();
        heap_.pop();
        if (!surface_.alive(top.face) || surface_.on_boundary(top.vertex) || !allowed(top.face, top.vertex, c0)) continue;
        carve(top.face, top.vertex);
        ++result.carved;
        for (const int v : near(top.vertex))
          if (!surface_.on_boundary(v)) propose(v, c0);
      }
      interior.erase(std::remove_if(interior.begin(), interior.end(), [&](int v) { return surface_.on_boundary(v); }),
                     interior.end());
      result.c0_used = c0;
    }
    return result;
  }

  Eigen::MatrixX3i boundary() const { return surface_.boundary(); }

 private:
  // Points within two Delaunay edges of v: the candidates' neighbourhood.
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
      if (!surface_.on_boundary(u)) continue;
      for (const int f : surface_.faces_at(u)) {
        const Triangle& t = surface_.face(f);
        // v must lie strictly behind the face, inside the solid.
        if (CGAL::orientation(surface_.exact(t[0]), surface_.exact(t[1]), surface_.exact(t[2]), surface_.exact(v)) !=
            CGAL::NEGATIVE)
          continue;
        if (!allowed(f, v, c0)) continue;
        heap_.push({gamma_indicator(surface_.point(t[0]), surface_.point(t[1]), surface_.point(t[2]), surface_.point(v)),
                    f, v});
      }
    }
  }

  // The triangle (a, b, c) is in γ([-1,1],[c0,1]) when no point lies in its
  // open symmetric lens N_γ(c0,c0): two balls of radius r/(1−|c0|) through
  // its circumcircle, centres on either side (Definition 3.1, Lemma 3.3).
  bool in_gamma(int a, int b, int c, double c0) const {
    const Eigen::Vector3d A = surface_.point(a), e1 = surface_.point(b) - A, e2 = surface_.point(c) - A,
                          n = e1.cross(e2);
    const double nn = n.squaredNorm();
    if (!(nn > 0)) return false;
    const Eigen::Vector3d O = A + (e1.squaredNorm() * e2.cross(n) + e2.squaredNorm() * n.cross(e1)) / (2.0 * nn);
    const double r = (A - O).norm();
    const bool open_triangle = c0 <= -1.0;  // the lens degenerates to the open triangle
    const double rho = open_triangle ? 0.0 : r / (1.0 - std::abs(c0));
    const double d = std::sqrt(std::max(rho * rho - r * r, 0.0));
    const Eigen::Vector3d unit = n / std::sqrt(nn);
    bool empty = true;
    surface_.points_near(Eigen::AlignedBox3d(O.array() - r, O.array() + r), [&](int q) {
      if (!empty || q == a || q == b || q == c) return;
      const Eigen::Vector3d x = surface_.point(q);
      if (!open_triangle) {
        if ((x - (O + d * unit)).norm() < rho && (x - (O - d * unit)).norm() < rho) empty = false;
      } else if (CGAL::orientation(surface_.exact(a), surface_.exact(b), surface_.exact(c), surface_.exact(q)) ==
                     CGAL::COPLANAR &&
                 BoundarySurface::Kernel::Triangle_3(surface_.exact(a), surface_.exact(b), surface_.exact(c))
                     .has_on(surface_.exact(q))) {
        empty = false;
      }
    });
    return empty;
  }

  bool allowed(int f, int v, double c0) const {
    const Triangle& t = surface_.face(f);
    Triangle sorted = t;
    std::sort(sorted.begin(), sorted.end());
    if (std::binary_search(keep_.begin(), keep_.end(), sorted)) return false;  // §5.7
    const std::vector<Triangle> fresh{{t[0], t[1], v}, {t[1], t[2], v}, {t[2], t[0], v}};
    for (const Triangle& n : fresh)
      if (!in_gamma(n[0], n[1], n[2], c0)) return false;
    // No point may fall outside, and the new triangles may not cross the
    // surface: the "simplices that cross a removed one" of §5.4.
    return !surface_.point_in_tetrahedron(t[0], t[1], t[2], v) && !surface_.meets_surface(fresh, {f});
  }

  void carve(int f, int v) {
    const Triangle t = surface_.face(f);
    surface_.remove_face(f);
    surface_.add_face({t[0], t[1], v});
    surface_.add_face({t[1], t[2], v});
    surface_.add_face({t[2], t[0], v});
  }

  const std::vector<std::vector<int>>& adjacency_;
  BoundarySurface surface_;
  std::priority_queue<Carve> heap_;
  std::vector<Triangle> keep_;  // sorted triples
};

}  // namespace

Augmentation augment_constriction(const Eigen::MatrixX3d& points, const std::vector<std::vector<int>>& adjacency,
                                  Eigen::MatrixX3i& boundary, std::vector<int>& interior_vertices,
                                  const AugmentationOptions& options) {
  if (interior_vertices.empty()) return {};
  Augmenter augmenter(points, adjacency, boundary, options.keep);
  const Augmentation result = augmenter.run(interior_vertices, options);
  boundary = augmenter.boundary();
  return result;
}

}  // namespace scanstation
