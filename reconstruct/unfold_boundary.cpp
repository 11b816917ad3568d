#include "reconstruct/unfold_boundary.h"

#include "reconstruct/boundary_surface.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Polygon_2_algorithms.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <optional>
#include <queue>
#include <set>
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
// The largest distance of a patch's points from its plane, over the loop's
// radius, for it to count as flat. Measured on the 26 closed genus-0 meshes
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

using EdgeApex = std::map<std::pair<int, int>, int>;  // directed edge → third vertex of its face

EdgeApex directed_edges(const std::vector<Triangle>& faces) {
  EdgeApex out;
  for (const Triangle& t : faces)
    for (std::size_t k = 0; k < 3; ++k) out[{t[k], t[(k + 1) % 3]}] = t[(k + 2) % 3];
  return out;
}

class Unfolder {
 public:
  Unfolder(const Eigen::MatrixX3d& P, const Eigen::MatrixX3i& F, const Eigen::MatrixXi& keep, double cos_fold)
      : P_(P), surface_(P, F), cos_fold_(cos_fold) {
    for (Eigen::Index k = 0; k < keep.rows(); ++k) fixed_.insert(sorted({keep(k, 0), keep(k, 1), keep(k, 2)}));
  }

  bool folded(int a, int b, int c, int d) const { return scanstation::folded(P_, cos_fold_, a, b, c, d); }

  BoundarySurface& surface() { return surface_; }

  /// All alive faces with a vertex in `vertices`.
  std::vector<int> star(const std::set<int>& vertices) const {
    std::set<int> faces;
    for (const int v : vertices)
      for (const int f : surface_.faces_at(v))
        if (surface_.alive(f)) faces.insert(f);
    return {faces.begin(), faces.end()};
  }

  /// Replaces the patch by a flat triangulation if that is valid and has
  /// fewer folds; false if the patch stays.
  bool retriangulate(const std::vector<int>& patch) {
    if (patch.size() > kMaxPatchFaces) return false;
    for (const int f : patch)
      if (fixed_.count(sorted(surface_.face(f)))) return false;
    // Directed edges of the patch → third vertex; the loop is the edges whose
    // reverse is not in the patch.
    std::vector<Triangle> faces;
    for (const int f : patch) faces.push_back(surface_.face(f));
    const EdgeApex inside = directed_edges(faces);
    std::map<int, int> next;
    for (const auto& [e, c] : inside)
      if (!inside.count({e.second, e.first}) && !next.emplace(e.first, e.second).second) return false;  // pinched
    if (next.size() < 3) return false;
    std::vector<int> loop{next.begin()->first};
    while (loop.size() <= next.size()) {
      const int v = next.at(loop.back());
      if (v == loop.front()) break;
      loop.push_back(v);
    }
    if (loop.size() != next.size()) return false;  // more than one loop
    std::set<int> vertices;
    for (const auto& [e, c] : inside) vertices.insert(e.first);
    std::vector<int> inner;
    for (const int v : vertices)
      if (!next.count(v)) inner.push_back(v);
    // A disk: V − E + F = 1, with E = (3F + L) / 2.
    const std::ptrdiff_t V = static_cast<std::ptrdiff_t>(vertices.size()), Fc = static_cast<std::ptrdiff_t>(patch.size());
    const std::ptrdiff_t E = (3 * Fc + static_cast<std::ptrdiff_t>(loop.size())) / 2;
    if (V - E + Fc != 1) return false;

    std::optional<std::vector<Triangle>> flat = flat_triangulation(loop, inner);
    if (!flat || flat->size() != patch.size()) return false;
    if (folds(directed_edges(*flat), loop) >= folds(inside, loop)) return false;
    for (const int f : patch) surface_.remove_face(f);
    if (!valid(*flat, loop)) {
      for (const Triangle& t : faces) surface_.add_face(t);
      return false;
    }
    for (const Triangle& t : *flat) surface_.add_face(t);
    return true;
  }

 private:
  // The constrained Delaunay triangulation of the loop and the inner
  // vertices projected on the plane of the loop's vector area, its
  // triangles inside the loop, counter-clockwise seen from the side the
  // vector area points to (the patch's outside): nullopt when the
  // projection is not a simple polygon with the inner vertices strictly
  // inside and apart.
  std::optional<std::vector<Triangle>> flat_triangulation(const std::vector<int>& loop,
                                                          const std::vector<int>& inner) const {
    Eigen::Vector3d origin = Eigen::Vector3d::Zero(), area = Eigen::Vector3d::Zero();
    for (const int i : loop) origin += P_.row(i).transpose();
    origin /= static_cast<double>(loop.size());
    for (std::size_t i = 0; i < loop.size(); ++i)
      area += (P_.row(loop[i]).transpose() - origin).cross(P_.row(loop[(i + 1) % loop.size()]).transpose() - origin);
    if (!(area.norm() > 0)) return std::nullopt;
    const Eigen::Vector3d n = area.normalized(), u = n.unitOrthogonal(), v = n.cross(u);
    const auto project = [&](int i) {
      const Eigen::Vector3d p = P_.row(i).transpose() - origin;
      return Kernel::Point_2(p.dot(u), p.dot(v));
    };
    // Only a patch that is nearly flat is a fold to undo; elsewhere the
    // surface may turn sharply for real (the edge of a thin plate).
    double radius = 0, height = 0;
    for (const int i : loop) radius = std::max(radius, (P_.row(i).transpose() - origin).norm());
    for (const auto& part : {loop, inner})
      for (const int i : part) height = std::max(height, std::abs((P_.row(i).transpose() - origin).dot(n)));
    if (height > kFlatness * radius) return std::nullopt;
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

  // Folds among the faces given as directed edge → third vertex, and across
  // the loop between them and the faces outside.
  std::size_t folds(const EdgeApex& inside, const std::vector<int>& loop) const {
    std::size_t count = 0;
    for (const auto& [e, c] : inside)
      if (e.first < e.second)
        if (const auto other = inside.find({e.second, e.first}); other != inside.end())
          count += folded(e.first, e.second, c, other->second);
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const int a = loop[i], b = loop[(i + 1) % loop.size()];
      const auto [outer, d] = surface_.face_with(b, a);
      if (outer >= 0) count += folded(a, b, inside.at({a, b}), d);
    }
    return count;
  }

  // Exact: no flat triangle, no chord between loop vertices that is an edge
  // of the rest of the surface, no improper meeting with the rest or among
  // themselves (the patch's faces are removed already).
  bool valid(const std::vector<Triangle>& flat, const std::vector<int>& loop) const {
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
    if (surface_.meets_surface(flat, {})) return false;
    for (std::size_t i = 0; i < flat.size(); ++i)
      for (std::size_t j = i + 1; j < flat.size(); ++j)
        if (surface_.box({flat[i][0], flat[i][1], flat[i][2]}).intersects(surface_.box({flat[j][0], flat[j][1], flat[j][2]})) &&
            surface_.improper(flat[i], flat[j]))
          return false;
    return true;
  }

  static Triangle sorted(Triangle t) {
    std::sort(t.begin(), t.end());
    return t;
  }

  const Eigen::MatrixX3d& P_;
  BoundarySurface surface_;
  double cos_fold_;
  std::set<Triangle> fixed_;
};

// Union–find over point ids, for grouping the folds.
int root(std::map<int, int>& parent, int v) {
  while (parent[v] != v) v = parent[v] = parent[parent[v]];
  return v;
}

}  // namespace

UnfoldStatistics unfold_boundary(const Eigen::MatrixX3d& P, Eigen::MatrixX3i& F, const Eigen::MatrixXi& keep,
                                 double fold_degrees) {
  UnfoldStatistics s;
  const double cos_fold = std::cos(fold_degrees * kPi / 180.0);
  const auto is_fold = [&](int a, int b, int c, int d) { return folded(P, cos_fold, a, b, c, d); };
  std::vector<std::pair<int, int>> folds;
  for_each_edge(P.rows(), F, [&](int lo, int hi, int c, int d) {
    if (is_fold(lo, hi, c, d)) folds.emplace_back(lo, hi);
  });
  s.folds_before = s.folds_after = folds.size();
  if (folds.empty()) return s;

  // Groups: fold vertices joined along folds and through shared faces.
  Unfolder unfolder(P, F, keep, cos_fold);
  BoundarySurface& surface = unfolder.surface();
  std::map<int, int> parent;
  for (const auto& [a, b] : folds) parent.emplace(a, a), parent.emplace(b, b);
  for (const auto& [a, b] : folds) parent[root(parent, a)] = root(parent, b);
  for (const auto& [v, p] : parent)
    for (const int f : surface.faces_at(v))
      for (const int w : surface.face(f))
        if (parent.count(w)) parent[root(parent, v)] = root(parent, w);
  std::map<int, std::set<int>> groups;
  for (const auto& [v, p] : parent) groups[root(parent, v)].insert(v);

  for (auto& [id, vertices] : groups) {
    ++s.patches;
    std::set<int> around = vertices;
    for (int growth = 0; growth <= kGrowths; ++growth) {
      const std::vector<int> patch = unfolder.star(around);
      if (unfolder.retriangulate(patch)) {
        ++s.retriangulated;
        break;
      }
      for (const int f : patch)
        for (const int w : surface.face(f)) around.insert(w);
    }
  }
  F = surface.boundary();
  s.folds_after = 0;
  for_each_edge(P.rows(), F, [&](int lo, int hi, int c, int d) { s.folds_after += is_fold(lo, hi, c, d); });
  return s;
}

}  // namespace scanstation
