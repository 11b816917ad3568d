#include "reconstruct/unfold_boundary.h"

#include "reconstruct/boundary_surface.h"
#include "reconstruct/shadow_embedding.h"
#include "reconstruct/triangle_set.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Polygon_2_algorithms.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>
#include <numeric>
#include <optional>
#include <queue>
#include <utility>
#include <vector>

namespace scanstation {

namespace {

using Kernel = BoundarySurface::Kernel;
using Triangle = BoundarySurface::Triangle;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, Kernel>;
using Fb = CGAL::Triangulation_face_base_with_info_2<int, Kernel, CGAL::Constrained_triangulation_face_base_2<Kernel>>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<Kernel, CGAL::Triangulation_data_structure_2<Vb, Fb>,
                                                      CGAL::Exact_predicates_tag>;

constexpr double kPi = 3.14159265358979323846;
// A patch of more faces is not a fold but a region the method cannot judge.
constexpr std::size_t kMaxPatchFaces = 400;
constexpr int kGrowths = 2;
// The largest distance of a patch's points from its plane, over the largest
// from their centroid, for it to count as flat. Measured on the 26 closed genus-0 meshes
// of CGAL's data: 0.25 keeps every recall within 0.1 points or better (no
// limit: dino −0.4, couplingdown −2.9), 0.1 undoes a third as many folds.
constexpr double kFlatness = 0.25;

// Faces (a, b, c) and (b, a, d) turn by more than the fold angle (its cosine given).
bool folded(const Eigen::MatrixX3d& P, double cos_fold, int a, int b, int c, int d) {
  const Eigen::Vector3d pa = P.row(a).transpose(), pb = P.row(b).transpose();
  const Eigen::Vector3d n1 = (pb - pa).cross(P.row(c).transpose() - pa);
  const Eigen::Vector3d n2 = (pa - pb).cross(P.row(d).transpose() - pb);
  return n1.dot(n2) < cos_fold * n1.norm() * n2.norm();
}

// The directed edges of some faces with the third vertex of each, sorted
// for lookup (a patch has at most a few thousand).
class DirectedEdges {
 public:
  struct Edge {
    int from, to, apex;
    bool operator<(const Edge& o) const { return std::tie(from, to) < std::tie(o.from, o.to); }
  };
  explicit DirectedEdges(const std::vector<Triangle>& faces) {
    for (const Triangle& t : faces)
      for (std::size_t k = 0; k < 3; ++k) edges_.push_back({t[k], t[(k + 1) % 3], t[(k + 2) % 3]});
    std::sort(edges_.begin(), edges_.end());
  }
  const std::vector<Edge>& all() const { return edges_; }
  /// The third vertex of the face on from → to; -1 if none.
  int apex(int from, int to) const {
    const auto it = std::lower_bound(edges_.begin(), edges_.end(), Edge{from, to, 0});
    return it != edges_.end() && it->from == from && it->to == to ? it->apex : -1;
  }

 private:
  std::vector<Edge> edges_;
};

// A patch's plane: through the centroid of its points, normal to its vector
// area (the sum of its faces', which for a disk is its boundary loop's).
struct Plane {
  Eigen::Vector3d origin, normal;
};

class Unfolder {
 public:
  Unfolder(BoundarySurface& surface, const Eigen::MatrixX3d& P, const Eigen::MatrixXi& keep, double cos_fold)
      : P_(P), surface_(surface), cos_fold_(cos_fold), fixed_(keep) {}

  bool folded(int a, int b, int c, int d) const { return scanstation::folded(P_, cos_fold_, a, b, c, d); }

  /// All alive faces with a vertex in `vertices`, in id order.
  std::vector<int> star(const std::vector<int>& vertices) const {
    std::vector<int> faces;
    for (const int v : vertices)
      for (const int f : surface_.faces_at(v))
        if (surface_.alive(f)) faces.push_back(f);
    std::sort(faces.begin(), faces.end());
    faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
    return faces;
  }

  /// Replaces the patch by a flat triangulation if that is valid and has
  /// fewer folds: how many fewer (the folds change only on the patch's edges
  /// and its loop's); 0 if the patch stays.
  std::size_t retriangulate(const std::vector<int>& patch) {
    if (patch.size() > kMaxPatchFaces) return 0;
    std::vector<Triangle> faces;
    for (const int f : patch) {
      faces.push_back(surface_.face(f));
      if (fixed_.contains(faces.back())) return 0;
    }
    std::vector<int> vertices;
    for (const Triangle& t : faces) vertices.insert(vertices.end(), t.begin(), t.end());
    std::sort(vertices.begin(), vertices.end());
    vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
    const std::optional<Plane> plane = flat_plane(faces, vertices);
    if (!plane) return 0;
    // The loop: the directed edges whose reverse is not in the patch.
    const DirectedEdges inside(faces);
    std::vector<std::pair<int, int>> next;  // loop edges by their start
    for (const auto& e : inside.all())
      if (inside.apex(e.to, e.from) < 0) next.emplace_back(e.from, e.to);
    for (std::size_t i = 1; i < next.size(); ++i)
      if (next[i].first == next[i - 1].first) return 0;  // pinched: the loop passes a vertex twice
    if (next.size() < 3) return 0;
    const auto successor = [&](int v) {
      const auto it = std::lower_bound(next.begin(), next.end(), std::pair{v, -1});
      return it != next.end() && it->first == v ? it->second : -1;
    };
    std::vector<int> loop{next.front().first};
    for (int v = successor(loop.back()); v != loop.front(); v = successor(v)) {
      if (v < 0 || loop.size() == next.size()) return 0;  // open (the input is no closed manifold)
      loop.push_back(v);
    }
    if (loop.size() != next.size()) return 0;  // more than one loop
    std::vector<int> inner;
    for (const int v : vertices)
      if (!std::binary_search(next.begin(), next.end(), std::pair{v, -1},
                              [](const auto& x, const auto& y) { return x.first < y.first; }))
        inner.push_back(v);
    // A disk: V − E + F = 1, with E = (3F + L) / 2.
    const std::ptrdiff_t V = static_cast<std::ptrdiff_t>(vertices.size()), Fc = static_cast<std::ptrdiff_t>(patch.size());
    const std::ptrdiff_t E = (3 * Fc + static_cast<std::ptrdiff_t>(loop.size())) / 2;
    if (V - E + Fc != 1) return 0;

    std::optional<std::vector<Triangle>> flat = flat_triangulation(*plane, loop, inner);
    if (!flat || flat->size() != patch.size()) return 0;
    const std::size_t before = folds(inside, loop), after = folds(DirectedEdges(*flat), loop);
    if (after >= before) return 0;
    for (const int f : patch) surface_.remove_face(f);
    if (!valid(*flat, loop, faces, plane->normal)) {
      for (const Triangle& t : faces) surface_.add_face(t);
      return 0;
    }
    for (const Triangle& t : *flat) surface_.add_face(t);
    return before - after;
  }

 private:
  // The patch's plane if the patch is nearly flat: every point within
  // kFlatness of the largest distance from the centroid. Only such a patch
  // is a fold to undo; elsewhere the surface may turn sharply for real (the
  // edge of a thin plate).
  std::optional<Plane> flat_plane(const std::vector<Triangle>& faces, const std::vector<int>& vertices) const {
    Plane plane{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
    for (const int v : vertices) plane.origin += P_.row(v).transpose();
    plane.origin /= static_cast<double>(vertices.size());
    for (const Triangle& t : faces) {
      const Eigen::Vector3d a = P_.row(t[0]).transpose() - plane.origin;
      plane.normal += a.cross(P_.row(t[1]).transpose() - plane.origin) +
                      (P_.row(t[1]).transpose() - plane.origin).cross(P_.row(t[2]).transpose() - plane.origin) +
                      (P_.row(t[2]).transpose() - plane.origin).cross(a);
    }
    if (!(plane.normal.norm() > 0)) return std::nullopt;
    plane.normal.normalize();
    double radius = 0, height = 0;
    for (const int v : vertices) {
      const Eigen::Vector3d p = P_.row(v).transpose() - plane.origin;
      radius = std::max(radius, p.norm());
      height = std::max(height, std::abs(p.dot(plane.normal)));
    }
    if (height > kFlatness * radius) return std::nullopt;
    return plane;
  }

  // The constrained Delaunay triangulation of the loop and the inner
  // vertices projected on the plane, its triangles inside the loop,
  // counter-clockwise seen from the side the normal points to (the patch's
  // outside): nullopt when the projection is not a simple polygon with the
  // inner vertices strictly inside and apart.
  std::optional<std::vector<Triangle>> flat_triangulation(const Plane& plane, const std::vector<int>& loop,
                                                          const std::vector<int>& inner) const {
    const Eigen::Vector3d u = plane.normal.unitOrthogonal(), v = plane.normal.cross(u);
    const auto project = [&](int i) {
      const Eigen::Vector3d p = P_.row(i).transpose() - plane.origin;
      return Kernel::Point_2(p.dot(u), p.dot(v));
    };
    std::vector<Kernel::Point_2> polygon;
    for (const int i : loop) polygon.push_back(project(i));
    if (!CGAL::is_simple_2(polygon.begin(), polygon.end(), Kernel()) ||
        CGAL::orientation_2(polygon.begin(), polygon.end(), Kernel()) != CGAL::COUNTERCLOCKWISE)
      return std::nullopt;
    Cdt cdt;
    std::vector<Cdt::Vertex_handle> corners;
    for (std::size_t i = 0; i < loop.size(); ++i) {
      corners.push_back(cdt.insert(polygon[i]));
      corners.back()->info() = loop[i];
    }
    for (std::size_t i = 0; i < loop.size(); ++i) cdt.insert_constraint(corners[i], corners[(i + 1) % loop.size()]);
    for (const int i : inner) {
      const Kernel::Point_2 q = project(i);
      if (CGAL::bounded_side_2(polygon.begin(), polygon.end(), q, Kernel()) != CGAL::ON_BOUNDED_SIDE) return std::nullopt;
      const auto before = cdt.number_of_vertices();
      const Cdt::Vertex_handle h = cdt.insert(q);
      if (cdt.number_of_vertices() == before) return std::nullopt;  // two points on one spot
      h->info() = i;
    }
    if (cdt.number_of_vertices() != loop.size() + inner.size()) return std::nullopt;  // constraints crossed
    // Inside: faces reached from the infinite one across an odd number of constraints.
    for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f) f->info() = -1;
    std::queue<Cdt::Face_handle> todo;
    cdt.infinite_face()->info() = 0;
    todo.push(cdt.infinite_face());
    while (!todo.empty()) {
      const Cdt::Face_handle f = todo.front();
      todo.pop();
      for (int i = 0; i < 3; ++i) {
        const Cdt::Face_handle g = f->neighbor(i);
        if (g->info() >= 0) continue;
        g->info() = f->info() + (cdt.is_constrained({f, i}) ? 1 : 0);
        todo.push(g);
      }
    }
    std::vector<Triangle> out;
    for (const auto f : cdt.finite_face_handles())
      if (f->info() % 2 == 1) out.push_back({f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()});
    return out;
  }

  // Folds among the faces and across the loop between them and the faces
  // outside.
  std::size_t folds(const DirectedEdges& inside, const std::vector<int>& loop) const {
    std::size_t count = 0;
    for (const auto& e : inside.all())
      if (e.from < e.to)
        if (const int d = inside.apex(e.to, e.from); d >= 0) count += folded(e.from, e.to, e.apex, d);
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const int a = loop[i], b = loop[(i + 1) % loop.size()];
      const auto [outer, d] = surface_.face_with(b, a);
      if (outer >= 0) count += folded(a, b, inside.apex(a, b), d);
    }
    return count;
  }

  // Exact: no flat triangle, no chord between loop vertices that is an edge
  // of the rest of the surface, no improper meeting with the rest or among
  // themselves (the patch's faces, `before`, are removed already). A flat
  // triangle that was one of them needs no test against the rest: neither
  // changed, and they met properly before (with 0.1% noise on CGAL's 26
  // meshes, 57k of 83k flat triangles tested were such).
  bool valid(const std::vector<Triangle>& flat, const std::vector<int>& loop, const std::vector<Triangle>& before,
             const Eigen::Vector3d& normal) const {
    std::map<int, int> next;  // along the loop
    for (std::size_t i = 0; i < loop.size(); ++i) next[loop[i]] = loop[(i + 1) % loop.size()];
    for (const Triangle& t : flat) {
      if (CGAL::collinear(surface_.exact(t[0]), surface_.exact(t[1]), surface_.exact(t[2]))) return false;
      for (std::size_t k = 0; k < 3; ++k) {
        const int a = t[k], b = t[(k + 1) % 3];
        const bool chord = next.count(a) && next.count(b) && next[a] != b && next[b] != a;
        if (chord && surface_.has_edge(a, b)) return false;
      }
    }
    const TriangleSet was(before);
    for (const Triangle& t : flat)  // one by one: each visits only the faces near it
      if (!was.contains(t) && surface_.meets_surface({t}, {})) return false;
    // Among themselves: from their shadow when it settles it (on laser
    // profiles, 100 meridians of 1000 points with 0.1% noise, the pairwise
    // test below was 8% of unfolding's instructions), else pair by pair.
    if (embedded_over_axis(P_, flat, loop, normal)) return true;
    std::vector<Eigen::AlignedBox3d> boxes;  // each once, not once per pair
    for (const Triangle& t : flat) boxes.push_back(surface_.box({t[0], t[1], t[2]}));
    for (std::size_t i = 0; i < flat.size(); ++i)
      for (std::size_t j = i + 1; j < flat.size(); ++j)
        if (boxes[i].intersects(boxes[j]) && surface_.improper(flat[i], flat[j])) return false;
    return true;
  }

  const Eigen::MatrixX3d& P_;
  BoundarySurface& surface_;
  double cos_fold_;
  TriangleSet fixed_;
};

}  // namespace

namespace {

std::vector<std::pair<int, int>> fold_edges(const Eigen::MatrixX3d& P, const Eigen::MatrixX3i& F, double cos_fold) {
  std::vector<std::pair<int, int>> folds;
  for (const MarkedEdge& e : select_edges(P.rows(), F, [&](int lo, int hi, int c, int d) {
         return static_cast<unsigned>(folded(P, cos_fold, lo, hi, c, d));
       }))
    folds.emplace_back(e.lo, e.hi);
  return folds;
}

UnfoldStatistics unfold(BoundarySurface& surface, const Eigen::MatrixX3d& P, Eigen::MatrixX3i& F,
                        const Eigen::MatrixXi& keep, double cos_fold, const std::vector<std::pair<int, int>>& folds) {
  UnfoldStatistics s;
  s.folds_before = s.folds_after = folds.size();
  if (folds.empty()) return s;
  // Groups: fold vertices joined along folds and through shared faces
  // (union–find over the fold vertices, numbered by their rank).
  Unfolder unfolder(surface, P, keep, cos_fold);
  std::vector<int> ends;
  for (const auto& [a, b] : folds) ends.insert(ends.end(), {a, b});
  std::sort(ends.begin(), ends.end());
  ends.erase(std::unique(ends.begin(), ends.end()), ends.end());
  const auto rank = [&](int v) {
    const auto it = std::lower_bound(ends.begin(), ends.end(), v);
    return it != ends.end() && *it == v ? static_cast<int>(it - ends.begin()) : -1;
  };
  std::vector<int> parent(ends.size());
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&](int i) {
    while (parent[static_cast<std::size_t>(i)] != i)
      i = parent[static_cast<std::size_t>(i)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
    return i;
  };
  for (const auto& [a, b] : folds) parent[static_cast<std::size_t>(root(rank(a)))] = root(rank(b));
  for (std::size_t i = 0; i < ends.size(); ++i)
    for (const int f : surface.faces_at(ends[i]))
      if (surface.alive(f))
        for (const int w : surface.face(f))
          if (const int j = rank(w); j >= 0) parent[static_cast<std::size_t>(root(static_cast<int>(i)))] = root(j);
  std::vector<std::vector<int>> groups(ends.size());
  for (std::size_t i = 0; i < ends.size(); ++i) groups[static_cast<std::size_t>(root(static_cast<int>(i)))].push_back(ends[i]);

  for (const std::vector<int>& group : groups) {
    if (group.empty()) continue;
    ++s.patches;
    std::vector<int> around = group;
    for (int growth = 0; growth <= kGrowths; ++growth) {
      const std::vector<int> patch = unfolder.star(around);
      if (const std::size_t undone = unfolder.retriangulate(patch); undone > 0) {
        ++s.retriangulated;
        s.folds_after -= undone;
        break;
      }
      for (const int f : patch) around.insert(around.end(), surface.face(f).begin(), surface.face(f).end());
      std::sort(around.begin(), around.end());
      around.erase(std::unique(around.begin(), around.end()), around.end());
    }
  }
  if (s.retriangulated > 0) F = surface.boundary();
  return s;
}

}  // namespace

UnfoldStatistics unfold_boundary(const Eigen::MatrixX3d& P, Eigen::MatrixX3i& F, const Eigen::MatrixXi& keep,
                                 double fold_degrees) {
  const double cos_fold = std::cos(fold_degrees * kPi / 180.0);
  const std::vector<std::pair<int, int>> folds = fold_edges(P, F, cos_fold);
  if (folds.empty()) return {};
  BoundarySurface surface(P, F);
  return unfold(surface, P, F, keep, cos_fold, folds);
}

UnfoldStatistics unfold_boundary(BoundarySurface& surface, const Eigen::MatrixX3d& P, Eigen::MatrixX3i& F,
                                 const Eigen::MatrixXi& keep, double fold_degrees) {
  const double cos_fold = std::cos(fold_degrees * kPi / 180.0);
  return unfold(surface, P, F, keep, cos_fold, fold_edges(P, F, cos_fold));
}

}  // namespace scanstation
