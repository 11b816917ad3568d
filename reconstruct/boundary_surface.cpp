#include "reconstruct/boundary_surface.h"

#include <tbb/parallel_invoke.h>

#include <CGAL/intersections.h>

#include <algorithm>
#include <cmath>
#include <span>

namespace scanstation {

namespace {
Eigen::AlignedBox3d bounds(const Eigen::MatrixX3d& P) {
  return Eigen::AlignedBox3d(P.colwise().minCoeff().transpose(), P.colwise().maxCoeff().transpose());
}
// About 32 triangles per grid cell: a closed surface through n points has
// about 2n triangles, so a cell of 8·sqrt(a) for the median triangle area a
// is crossed by some 32 of them (the surface is 2D: 64 a of it per cell).
// The queries (a flip's quad, a carve's tetrahedron, an unfolded patch) are
// mostly larger than the median triangle, and each probe of a cell is a
// hash lookup, a cache miss, while a cell's entries are read in a row: with
// two triangles per cell (2·sqrt(a), the former size) the flips' tests on
// man probed 300 cells and read 860 entries per query, over eight levels
// (faces longer than two cells go up a level); with 8·sqrt(a), 72 cells
// and 660 entries, nearly all on the first level. CGAL's 26 closed genus-0
// meshes: flips 0.35× → 0.30× of CGAL's Delaunay time (4·sqrt(a): 0.31×,
// 12·sqrt(a): 0.31×); the answers are the same (the grid only filters).
// The median, not the box: a far outlier makes the box's area (the former
// measure) millions of times the surface's, and every query then met every
// face. Without triangles, the box's surface area stands in, at the same
// 32 points per cell.
double cell_size(const Eigen::MatrixX3d& P, const Eigen::MatrixX3i& faces) {
  if (faces.rows() == 0) {
    const Eigen::Vector3d extent = (P.colwise().maxCoeff() - P.colwise().minCoeff()).transpose();
    const double area = 2.0 * (extent.x() * extent.y() + extent.y() * extent.z() + extent.z() * extent.x());
    return std::max(std::sqrt(32.0 * area / static_cast<double>(std::max<Eigen::Index>(P.rows(), 1))), 1e-300);
  }
  std::vector<double> area(static_cast<std::size_t>(faces.rows()));
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const Eigen::Vector3d a = P.row(faces(f, 0)), b = P.row(faces(f, 1)), c = P.row(faces(f, 2));
    area[static_cast<std::size_t>(f)] = 0.5 * (b - a).cross(c - a).norm();
  }
  const auto middle = area.begin() + static_cast<std::ptrdiff_t>(area.size() / 2);
  std::nth_element(area.begin(), middle, area.end());
  return std::max(8.0 * std::sqrt(*middle), 1e-300);
}
}  // namespace

BoxGrid surface_grid(const Eigen::MatrixX3d& P, const Eigen::MatrixX3i& faces) {
  return BoxGrid(bounds(P), cell_size(P, faces));
}

PointTree::PointTree(const Eigen::MatrixX3d& P) : items_(static_cast<std::size_t>(P.rows())) {
  for (std::size_t i = 0; i < items_.size(); ++i)
    items_[i] = {P.row(static_cast<Eigen::Index>(i)).transpose(), static_cast<int>(i)};
  // A balanced split at the middle index needs fewer than 4n/kLeaf nodes.
  nodes_.resize(std::max<std::size_t>(1, 4 * items_.size() / kLeaf + 4));
  if (!items_.empty()) build(0, 0, static_cast<int>(items_.size()));
}

// The points are partitioned as (position, id) pairs, not as ids into the
// positions: the selection then reads memory in order (on bunny00's 37.7k
// points the build fell from 8 to 3 ms, and augmentation pays it in full
// when a handful of points is left inside), and the pairs are the tree's
// leaves as they are. The two halves of a large node are built on both
// cores; they own disjoint ranges and nodes, so the tree is the same as
// from one.
void PointTree::build(int node, int begin, int end) {
  Node& n = nodes_[static_cast<std::size_t>(node)];
  n.begin = begin;
  n.end = end;
  n.box.setEmpty();
  for (int k = begin; k < end; ++k) n.box.extend(items_[static_cast<std::size_t>(k)].position);
  if (end - begin <= kLeaf) return;
  int axis = 0;
  n.box.sizes().maxCoeff(&axis);
  const int mid = begin + (end - begin) / 2;
  std::nth_element(items_.begin() + begin, items_.begin() + mid, items_.begin() + end,
                   [axis](const Item& a, const Item& b) { return a.position[axis] < b.position[axis]; });
  const auto left = [&] { build(2 * node + 1, begin, mid); };
  const auto right = [&] { build(2 * node + 2, mid, end); };
  if (end - begin >= kParallelPoints) {
    tbb::parallel_invoke(left, right);
  } else {
    left();
    right();
  }
}

BoundarySurface::BoundarySurface(const Eigen::MatrixX3d& P, const Eigen::MatrixX3i& boundary,
                                 std::shared_ptr<const PointTree> points)
    : P_(P),
      points_(std::move(points)),
      faces_grid_(surface_grid(P, boundary)),
      faces_at_(static_cast<std::size_t>(P.rows())),
      on_boundary_(static_cast<std::size_t>(P.rows()), 0) {
  cgal_.reserve(static_cast<std::size_t>(P.rows()));
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    cgal_.emplace_back(P(i, 0), P(i, 1), P(i, 2));
  }
  // Each point's face list in one allocation, with room for a few faces of
  // later edits, instead of growing it face by face.
  std::vector<int> count(static_cast<std::size_t>(P.rows()), 0);
  for (Eigen::Index f = 0; f < boundary.rows(); ++f)
    for (int k = 0; k < 3; ++k) ++count[static_cast<std::size_t>(boundary(f, k))];
  for (std::size_t v = 0; v < count.size(); ++v)
    if (count[v] > 0) faces_at_[v].reserve(static_cast<std::size_t>(count[v]) + 2);
  // Room for the faces of later edits too (a flip adds two, a carve three):
  // growing past the reserve doubles the arrays.
  const auto room = static_cast<std::size_t>(boundary.rows() + boundary.rows() / 4 + 16);
  faces_.reserve(room);
  alive_.reserve(room);
  for (Eigen::Index f = 0; f < boundary.rows(); ++f) add_face({boundary(f, 0), boundary(f, 1), boundary(f, 2)});
  built_faces_ = faces_.size();
}

Eigen::AlignedBox3d BoundarySurface::box(std::initializer_list<int> ids) const {
  Eigen::AlignedBox3d b;
  for (const int i : ids) b.extend(point(i));
  return b;
}

int BoundarySurface::add_face(const Triangle& t) {
  const int id = static_cast<int>(faces_.size());
  faces_.push_back(t);
  alive_.push_back(1);
  ++alive_faces_;
  for (const int v : t) {
    faces_at_[static_cast<std::size_t>(v)].push_back(id);
    on_boundary_[static_cast<std::size_t>(v)] = 1;
  }
  faces_grid_.insert(id, box({t[0], t[1], t[2]}));
  return id;
}

void BoundarySurface::remove_face(int id) {
  alive_[static_cast<std::size_t>(id)] = 0;
  --alive_faces_;
  const Triangle& t = faces_[static_cast<std::size_t>(id)];
  faces_grid_.erase(id, box({t[0], t[1], t[2]}));
  for (const int v : t) {
    auto& at = faces_at_[static_cast<std::size_t>(v)];
    at.erase(std::remove(at.begin(), at.end(), id), at.end());
  }
}

bool BoundarySurface::has_edge(int u, int v) const {
  for (const int f : faces_at(u))
    if (alive(f) && std::find(face(f).begin(), face(f).end(), v) != face(f).end()) return true;
  return false;
}

std::pair<int, int> BoundarySurface::face_with(int a, int b) const {
  for (const int f : faces_at(a)) {
    if (!alive(f)) continue;
    const Triangle& t = face(f);
    for (std::size_t k = 0; k < 3; ++k)
      if (t[k] == a && t[(k + 1) % 3] == b) return {f, t[(k + 2) % 3]};
  }
  return {-1, -1};
}

bool BoundarySurface::improper(const Triangle& s, const Triangle& t) const {
  std::array<int, 3> shared{};
  int n = 0;
  for (const int a : s)
    if (std::find(t.begin(), t.end(), a) != t.end()) shared[static_cast<std::size_t>(n++)] = a;
  const auto tri = [&](const Triangle& x) { return Kernel::Triangle_3(exact(x[0]), exact(x[1]), exact(x[2])); };
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
    // Two triangles sharing one vertex meet elsewhere iff an edge opposite the
    // shared vertex meets the other triangle.
    const Kernel::Segment_3 es(exact(other(s, 0)), exact(other(s, 1))), et(exact(other(t, 0)), exact(other(t, 1)));
    return CGAL::do_intersect(es, tri(t)) || CGAL::do_intersect(et, tri(s));
  }
  // Sharing an edge: they overlap iff coplanar and folded onto one side.
  const auto &a = exact(shared[0]), &b = exact(shared[1]), &x = exact(other(s, 0)), &y = exact(other(t, 0));
  return CGAL::orientation(a, b, x, y) == CGAL::COPLANAR && CGAL::coplanar_orientation(a, b, x, y) == CGAL::POSITIVE;
}

bool BoundarySurface::point_in_tetrahedron(int a, int b, int c, int d) const {
  // q lies in the closed tetrahedron iff no face has it strictly on the side
  // away from the opposite vertex: four orientation predicates, whose exact
  // fallback (on nearly flat tetrahedra, as between the points of a densely
  // scanned flat face) is far cheaper than that of Tetrahedron_3's
  // bounded-side test, which solves for barycentric coordinates in rationals.
  const Kernel::Point_3 &A = exact(a), &B = exact(b), &C = exact(c), &D = exact(d);
  const CGAL::Orientation outside = -CGAL::orientation(A, B, C, D);
  const Eigen::AlignedBox3d region = box({a, b, c, d});
  return !points().visit(region, [&](int q, const Eigen::Vector3d&) {
    // The box test is only a cheap filter; the exact predicates decide.
    if (q == a || q == b || q == c || q == d) return true;
    const Kernel::Point_3& Q = exact(q);
    return CGAL::orientation(A, B, C, Q) == outside || CGAL::orientation(A, B, Q, D) == outside ||
           CGAL::orientation(A, Q, C, D) == outside || CGAL::orientation(Q, B, C, D) == outside;
  });
}

namespace {

// The plane of a triangle, for a floating-point filter in front of the exact
// tests: a triangle whose three vertices lie strictly on one side of it, by
// far more than the rounding of the test, cannot meet it. The error of
// n·(p − a) with n = (b − a)×(c − a) stays below a few units of roundoff
// times |b − a||c − a||p − a|; the margin is 10^-12 of that, about 4500
// times larger. The lengths are taken in the 1-norm, which is at least the
// Euclidean one, so the margin only grows, and no square root is taken: the
// filter runs on every face a flip's or carve's box meets (the roots were
// the largest part of its time). Overflow gives no finite answer and no
// verdict.
double length_bound(const Eigen::Vector3d& v) { return v.cwiseAbs().sum(); }
struct PlaneFilter {
  PlaneFilter(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c)
      : a(a), n((b - a).cross(c - a)), scale(1e-12 * length_bound(b - a) * length_bound(c - a)) {}
  // +1 or −1 when all of q (at least one) lie clearly on that side, 0 when
  // undecided.
  int side(std::span<const Eigen::Vector3d> q) const {
    int above = 0, below = 0;
    for (const Eigen::Vector3d& p : q) {
      const double s = n.dot(p - a), margin = scale * length_bound(p - a);
      above += s > margin;
      below += s < -margin;
    }
    const int all = static_cast<int>(q.size());
    return all == 0 ? 0 : above == all ? 1 : below == all ? -1 : 0;
  }
  // +1 or −1 when the box lies clearly on that side: then so do the
  // vertices of any triangle in it. The box's reach along n is Σ|n_i|·h_i;
  // the margin is that of side() for the box's farthest point from a.
  int side(const Eigen::AlignedBox3d& box) const {
    const Eigen::Vector3d c = box.center(), h = 0.5 * box.sizes();
    const double s = n.dot(c - a), reach = n.cwiseAbs().dot(h);
    const double margin = 2.0 * scale * (length_bound(c - a) + length_bound(h));
    return s - reach > margin ? 1 : s + reach < -margin ? -1 : 0;
  }
  Eigen::Vector3d a, n;
  double scale;
};

}  // namespace

bool BoundarySurface::meets_faces(const std::vector<Triangle>& fresh, std::initializer_list<int> except,
                                  const BoxGrid& faces) const {
  Eigen::AlignedBox3d region;
  std::vector<Eigen::AlignedBox3d> boxes;
  std::vector<PlaneFilter> planes;
  for (const Triangle& t : fresh) {
    boxes.push_back(box({t[0], t[1], t[2]}));
    region.extend(boxes.back());
    planes.emplace_back(point(t[0]), point(t[1]), point(t[2]));
  }
  std::vector<char> near(fresh.size());  // per fresh triangle: its box may meet the face's
  // The corners of x that are no corners of y.
  std::array<Eigen::Vector3d, 3> corners;
  const auto unshared = [&](const Triangle& x, const Triangle& y) {
    std::size_t n = 0;
    for (const int v : x)
      if (std::find(y.begin(), y.end(), v) == y.end()) corners[n++] = point(v);
    return std::span<const Eigen::Vector3d>(corners.data(), n);
  };
  return !faces.visit(region, [&](int g, const Eigen::AlignedBox3d& other_box) {
    // The box as filed first: near a long triangle most faces lie clearly
    // on one side of its plane, told without reading the face (on a
    // chalice of 100k points, 64% of the pairs of boxes that met).
    bool any = false;
    for (std::size_t k = 0; k < fresh.size(); ++k) {
      near[k] = boxes[k].intersects(other_box) && planes[k].side(other_box) == 0;
      any = any || near[k];
    }
    if (!any || !alive(g) || std::find(except.begin(), except.end(), g) != except.end()) return true;
    const Triangle& other = face(g);
    for (std::size_t k = 0; k < fresh.size(); ++k) {
      if (!near[k]) continue;
      // A face whose vertices other than those it shares with t lie clearly
      // on one side of t's plane meets t only in the shared ones: the long
      // triangles of webs have boxes that meet hundreds of faces far from
      // their plane, and a flip's new triangles are tested against every
      // face around their corners, most of them sharing one. The same holds
      // with the two triangles' roles swapped: a face sharing a corner with
      // t often has its other two on both sides of t's plane while t's own
      // lie on one side of the face's (two thirds of the exact tests of the
      // flips and carves on CGAL's real meshes went).
      const Triangle& t = fresh[k];
      if (planes[k].side(unshared(other, t)) != 0) continue;
      if (PlaneFilter(point(other[0]), point(other[1]), point(other[2])).side(unshared(t, other)) != 0) continue;
      if (improper(t, other)) return false;
    }
    return true;
  });
}

Eigen::MatrixX3i BoundarySurface::boundary() const {
  std::vector<Triangle> live;
  for (std::size_t f = 0; f < faces_.size(); ++f)
    if (alive_[f]) live.push_back(faces_[f]);
  Eigen::MatrixX3i out(static_cast<Eigen::Index>(live.size()), 3);
  for (std::size_t f = 0; f < live.size(); ++f) out.row(static_cast<Eigen::Index>(f)) << live[f][0], live[f][1], live[f][2];
  return out;
}

}  // namespace scanstation
