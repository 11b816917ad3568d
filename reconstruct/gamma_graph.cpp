#include "reconstruct/gamma_graph.h"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_cell_base_with_info_3.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <set>
#include <string>
#include <type_traits>
#include <vector>

#include "core/errors.h"
#include "core/predicates.h"
#include "core/unique_points.h"
#include "core/unit_scale.h"

namespace scanstation {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
constexpr double kPi = 3.14159265358979323846;

// ---------------------------------------------------------------------------
// GammaTraits: the predicates and constructions of the pencil, per dimension.
// A simplex is an array of D vertex positions; side A is CGAL's positive side
// (2D: left of s[0] → s[1]; 3D: where (s1-s0)×(s2-s0) points).

enum class OnPlane { outside, disc, blocked };  // vertex in S's hyperplane

template <int D>
struct GammaTraits;

template <>
struct GammaTraits<2> {
  using Vec = Eigen::Vector2d;
  using Simplex = std::array<Vec, 2>;
  static K::Point_2 cg(const Vec& p) { return {p.x(), p.y()}; }

  static bool is_simplex(const Simplex&) { return true; }  // distinct points
  static void frame(const Simplex& s, Vec& m, Vec& n, double& r) {
    m = 0.5 * (s[0] + s[1]);
    const Vec d = s[1] - s[0];
    r = 0.5 * d.norm();
    n = Vec(-d.y(), d.x()) / d.norm();
  }
  static int side(const Simplex& s, const Vec& p) {
    return static_cast<int>(CGAL::orientation(cg(s[0]), cg(s[1]), cg(p)));
  }
  // +1 outside the smallest ball touching s, 0 on it, -1 inside.
  static int power_sign(const Simplex& s, const Vec& p) {
    // |p-m|² - r² = (p-a)·(p-b); the double is trusted far from 0 (a filter
    // with a 4500 ulp margin), else the exact predicate decides.
    const Vec u = p - s[0], v = p - s[1];
    const double dot = u.dot(v);
    if (std::abs(dot) > 1e-12 * u.norm() * v.norm()) return dot > 0 ? 1 : -1;
    return -static_cast<int>(CGAL::side_of_bounded_circle(cg(s[0]), cg(s[1]), cg(p)));
  }
  static OnPlane on_plane(const Simplex& s, const Vec& p) {
    return CGAL::collinear_are_strictly_ordered_along_line(cg(s[0]), cg(p), cg(s[1])) ? OnPlane::blocked
                                                                                        : OnPlane::outside;
  }
  // Sign of hi - lo when hi is realised by `a` (side A) and lo by `b` (side B):
  // b lies inside the ball through s and a exactly when hi < lo.
  static int tie_sign(const Simplex& s, const Vec& a, const Vec& b) {
    return static_cast<int>(CGAL::side_of_bounded_circle(cg(s[0]), cg(s[1]), cg(a), cg(b))) * -1;
  }
};

template <>
struct GammaTraits<3> {
  using Vec = Eigen::Vector3d;
  using Simplex = std::array<Vec, 3>;
  static K::Point_3 cg(const Vec& p) { return {p.x(), p.y(), p.z()}; }

  static bool is_simplex(const Simplex& s) { return !CGAL::collinear(cg(s[0]), cg(s[1]), cg(s[2])); }
  static void frame(const Simplex& s, Vec& m, Vec& n, double& r) {
    const Vec u = s[1] - s[0], v = s[2] - s[0], w = u.cross(v);
    m = s[0] + (u.squaredNorm() * v.cross(w) + v.squaredNorm() * w.cross(u)) / (2.0 * w.squaredNorm());
    r = (m - s[0]).norm();
    n = w.normalized();
  }
  static int side(const Simplex& s, const Vec& p) {
    return static_cast<int>(CGAL::orientation(cg(s[0]), cg(s[1]), cg(s[2]), cg(p)));
  }
  static int power_sign(const Simplex& s, const Vec& p) {
    // (|p-m|² - r²)·|w|² = |d|²|w|² - |u|² d·(v×w) - |v|² d·(w×u), a polynomial
    // in coordinate differences: trusted when it clears 1e-12 of the sum of
    // its terms' magnitudes (forward error < 40 ulp of that sum), else exact.
    const Vec u = s[1] - s[0], v = s[2] - s[0], d = p - s[0], w = u.cross(v);
    const Vec vw = v.cross(w), wu = w.cross(u);
    const double t0 = d.squaredNorm() * w.squaredNorm(), t1 = u.squaredNorm() * d.dot(vw),
                 t2 = v.squaredNorm() * d.dot(wu);
    const double val = t0 - t1 - t2;
    const double mag = t0 + u.squaredNorm() * d.norm() * vw.norm() + v.squaredNorm() * d.norm() * wu.norm();
    if (std::abs(val) > 1e-12 * mag) return val > 0 ? 1 : -1;
    return -static_cast<int>(CGAL::side_of_bounded_sphere(cg(s[0]), cg(s[1]), cg(s[2]), cg(p)));
  }
  // p (in s's plane) strictly inside the triangle.
  static bool in_open_triangle(const Simplex& s, const Vec& p) {
    const auto a = cg(s[0]), b = cg(s[1]), c = cg(s[2]), q = cg(p);
    return CGAL::coplanar_orientation(a, b, c, q) == CGAL::POSITIVE &&
           CGAL::coplanar_orientation(b, c, a, q) == CGAL::POSITIVE &&
           CGAL::coplanar_orientation(c, a, b, q) == CGAL::POSITIVE;
  }
  static OnPlane on_plane(const Simplex& s, const Vec& p) {
    if (in_open_triangle(s, p)) return OnPlane::blocked;
    return CGAL::coplanar_side_of_bounded_circle(cg(s[0]), cg(s[1]), cg(s[2]), cg(p)) == CGAL::ON_BOUNDED_SIDE
               ? OnPlane::disc
               : OnPlane::outside;
  }
  static int tie_sign(const Simplex& s, const Vec& a, const Vec& b) {
    return -static_cast<int>(CGAL::side_of_bounded_sphere(cg(s[0]), cg(s[1]), cg(s[2]), cg(a), cg(b)));
  }
};

// ---------------------------------------------------------------------------
// The pencil profile of one simplex (see the header).

struct Profile {
  double lo = -1, hi = 1;
  int arg_lo = -1, arg_hi = -1;  // vertices realising lo / hi
  bool blocked = false;          // a vertex in the open simplex
  bool disc = false;             // 3D: a coplanar vertex inside the circumcircle
};

template <int D>
struct Pencil {
  using T = GammaTraits<D>;
  using Vec = typename T::Vec;
  typename T::Simplex s;
  Vec m, n;
  double r = 0;

  explicit Pencil(const typename T::Simplex& simplex) : s(simplex) { T::frame(s, m, n, r); }

  // t_p of a vertex strictly on side `side`: sign exact, magnitude a double
  // kept inside (0,1) so that the half-spaces t = ±1 stay exact.
  double t_value(const Vec& p, int side) const {
    const int pw = T::power_sign(s, p);
    if (pw == 0) return 0.0;
    const Vec d = p - s[0];
    const double power = std::abs(d.squaredNorm() + 2.0 * d.dot(s[0] - m));  // | |p-m|² - r² |
    const double h = std::abs((p - m).dot(n));
    const double u = power / (2.0 * h * r);  // centre offset / r; inf when h == 0
    double mag = u < 1.0 ? u * u / (std::sqrt(1.0 + u * u) * (std::sqrt(1.0 + u * u) + 1.0))
                         : 1.0 - 1.0 / std::sqrt(1.0 + u * u);  // = 1 - r/R
    if (!(mag == mag)) mag = 1.0;
    constexpr double kBelowOne = 1.0 - 0x1p-53;  // largest double < 1; the lower bound is normal (no denormal stalls)
    mag = std::clamp(mag, std::numeric_limits<double>::min(), kBelowOne);
    return side * pw * mag;
  }

  // Adds one vertex (index i, not a vertex of s) to the profile.
  void add(Profile& pr, int i, const Vec& p) const {
    const int sd = T::side(s, p);
    if (sd == 0) {
      const OnPlane where = T::on_plane(s, p);
      pr.blocked |= where == OnPlane::blocked;
      pr.disc |= where == OnPlane::disc;
      return;
    }
    const double t = t_value(p, sd);
    if (sd > 0 && (pr.arg_hi < 0 || t < pr.hi)) pr.hi = t, pr.arg_hi = i;
    if (sd < 0 && (pr.arg_lo < 0 || t > pr.lo)) pr.lo = t, pr.arg_lo = i;
  }

  // Makes sign(hi - lo) exact: equality means co-spherical vertices on both
  // sides (one empty ball), which decides whether c'1 is ≥ 0.
  void finish(Profile& pr, const std::vector<Vec>& P) const {
    if (pr.arg_hi < 0 || pr.arg_lo < 0) return;
    const int sg = T::tie_sign(s, P[pr.arg_hi], P[pr.arg_lo]);
    if (sg == 0) pr.lo = pr.hi;
    if (sg > 0 && !(pr.hi > pr.lo)) pr.lo = std::nextafter(pr.hi, -2.0);
    if (sg < 0 && !(pr.hi < pr.lo)) pr.lo = std::nextafter(pr.hi, 2.0);
  }
};

// (c'0, c'1) of Definition 3.3 under the reading documented in the header.
std::optional<Eigen::Vector2d> largest_empty(const Profile& pr) {
  if (pr.blocked) return std::nullopt;
  const double a = pr.hi, b = -pr.lo;
  if (pr.disc) {  // only half-spaces avoid a coplanar in-circle vertex
    if (a == 1 && b == 1) return Eigen::Vector2d(1, 1);
    if (a == 1 || b == 1) return Eigen::Vector2d(-1, 1);
    return Eigen::Vector2d(std::max(a, b), -1);
  }
  if (pr.hi >= pr.lo) return Eigen::Vector2d(std::min(a, b), std::max(a, b));
  return Eigen::Vector2d(std::max(a, b), std::min(a, b));
}

// Definition 3.1 on the profile for the balls of parameters t0, t1 of the
// pencil: their union when c1 ≥ 0, else their intersection.
bool balls_empty(const Profile& pr, double t0, double t1, bool intersection) {
  if (pr.blocked) return false;
  const double lo = std::min(t0, t1), hi = std::max(t0, t1);
  const bool half0 = std::abs(t0) == 1, half1 = std::abs(t1) == 1;
  if (!intersection) return !(pr.disc && !(half0 && half1)) && pr.lo <= lo && hi <= pr.hi;  // B0 ∪ B1
  return !(pr.disc && !half0 && !half1) && lo <= pr.hi && pr.lo <= hi;                      // B0 ∩ B1
}

// Definition 3.1: t1 = c1, t0 = -c0 or the mirror image.
bool neighborhood_empty(const Profile& pr, double c0, double c1) {
  return balls_empty(pr, -c0, c1, c1 < 0) || balls_empty(pr, c0, -c1, c1 < 0);
}

// ---------------------------------------------------------------------------
// Input: finite, de-duplicated points.

template <int D>
struct Input {
  std::vector<typename GammaTraits<D>::Vec> P;  // distinct positions
  std::vector<int> id;                          // row of P[u] in the caller's V
};

template <int D>
Input<D> prepare(const Eigen::Matrix<double, Eigen::Dynamic, D>& V) {
  if (!V.allFinite()) throw InvalidInput("gamma graph: the point set holds a non-finite coordinate");
  Eigen::MatrixX3d V3 = Eigen::MatrixX3d::Zero(V.rows(), 3);
  V3.leftCols(D) = V;
  std::vector<Eigen::Index> first, map;
  unique_points(V3, first, map);
  // Pencils, lens balls and t_p are built in doubles: at 1e±300 their
  // squared lengths would overflow or underflow (the 3D hull of 200 points
  // came out with 638 triangles instead of 56). The exact scale keeps every
  // predicate's answer and every t_p, a ratio of lengths.
  const double scale = unit_scale(V);
  Input<D> in;
  for (Eigen::Index f : first) {
    in.P.push_back(V.row(f).transpose() * scale);
    in.id.push_back(static_cast<int>(f));
  }
  return in;
}

void check_parameter(double c, const char* name) {
  if (!(c >= -1 && c <= 1))
    throw InvalidInput(std::string("gamma graph: parameter ") + name + " = " + std::to_string(c) +
                       " lies outside [-1, 1]");
}

template <int D>
using Index = std::array<int, D>;

template <int D>
struct Candidate {
  Index<D> s;  // ascending indices into Input::P
  Profile profile;
};

template <int D>
typename GammaTraits<D>::Simplex positions(const Input<D>& in, const std::type_identity_t<Index<D>>& s) {
  typename GammaTraits<D>::Simplex x;
  for (int i = 0; i < D; ++i) x[i] = in.P[s[i]];
  return x;
}

// Profile of s against every vertex: O(N). Used for degenerate clusters.
template <int D>
Profile scan_profile(const Input<D>& in, const std::type_identity_t<Index<D>>& s) {
  const Pencil<D> pencil(positions(in, s));
  Profile pr;
  for (int i = 0; i < static_cast<int>(in.P.size()); ++i)
    if (std::find(s.begin(), s.end(), i) == s.end()) pencil.add(pr, i, in.P[i]);
  pencil.finish(pr, in.P);
  return pr;
}

// Profile of a simplex from the vertices that bound it (−1 and s's own
// skipped).
template <int D, typename Vertices>
Profile profile_among(const Input<D>& in, const std::type_identity_t<Index<D>>& s, const Vertices& bounding) {
  const Pencil<D> pencil(positions(in, s));
  Profile pr;
  for (int v : bounding)
    if (v >= 0 && std::find(s.begin(), s.end(), v) == s.end()) pencil.add(pr, v, in.P[v]);
  pencil.finish(pr, in.P);
  return pr;
}

// Profile of a Delaunay simplex from its opposite vertices (Theorem 3.2).
template <int D>
Profile delaunay_profile(const Input<D>& in, const std::type_identity_t<Index<D>>& s, std::initializer_list<int> opposite) {
  return profile_among<D>(in, s, opposite);
}

template <int D>
Index<D> sorted(Index<D> s) {
  std::sort(s.begin(), s.end());
  return s;
}

// Union-find over cell numbers, for clusters of co-spherical cells.
struct Clusters {
  std::vector<int> parent;
  int add() {
    parent.push_back(static_cast<int>(parent.size()));
    return parent.back();
  }
  int find(int x) { return parent[x] == x ? x : parent[x] = find(parent[x]); }
  void join(int a, int b) { parent[find(a)] = find(b); }
};

// The vertex sets of the clusters of more than one cell, by root: a single
// cell's subsets are its own faces, Delaunay simplices already. Cells are
// numbered 0..cells−1; vertices_of(t, set) adds cell t's finite vertices.
template <typename VerticesOf>
std::map<int, std::set<int>> cluster_groups(Clusters& uf, int cells, VerticesOf&& vertices_of) {
  std::vector<int> size(static_cast<std::size_t>(cells), 0);
  for (int t = 0; t < cells; ++t) ++size[static_cast<std::size_t>(uf.find(t))];
  std::map<int, std::set<int>> groups;
  for (int t = 0; t < cells; ++t)
    if (const int root = uf.find(t); size[static_cast<std::size_t>(root)] > 1) vertices_of(t, groups[root]);
  return groups;
}

// The simplices found so far, to tell a cluster's new subsets from them
// (built only when there are clusters: degenerate input).
template <int D>
std::set<Index<D>> simplices_of(const std::vector<Candidate<D>>& out) {
  std::set<Index<D>> seen;
  for (const Candidate<D>& c : out) seen.insert(c.s);
  return seen;
}

// All k-subsets of each cluster's vertex set that are not Delaunay simplices
// (degenerate input only), each profiled by `profile` (given the cluster's
// key and points), which needs only the points that bound it:
// In the plane the cluster's own points bound such a chord: they lie on the
// empty circle C on both sides of it (a chord with them all on one side is
// a side of the cluster's polygon, a Delaunay edge), every other point lies
// strictly outside C, so a disc of the chord's pencil grown past C on
// either side takes in a cluster point first. (A square lattice of 90k
// points: 114 s for the Gabriel graph with a scan of every point per
// chord, 1 s so.) In space so does a triangle with cluster points on both
// sides of its plane; one with them all on one side lies in a face of the
// cluster's polytope, whose points are on one circle c, so its pencil is
// that of the face's Delaunay triangles: the spheres through c. The first
// point such a sphere takes in beyond the cluster lies on an empty sphere
// through c, so it makes a Delaunay cell with a triangle of that face: it
// is the apex of a cell across the cluster's boundary. So a cluster of
// finite cells is bounded by its points and those apexes.
template <int D>
void add_cluster_subsets(const Input<D>& in, const std::map<int, std::set<int>>& groups,
                         const std::function<Profile(int root, const std::vector<int>& points, const Index<D>& s)>& profile,
                         std::set<Index<D>>& seen, std::vector<Candidate<D>>& out) {
  for (const auto& [root, vs] : groups) {
    if (static_cast<int>(vs.size()) <= D + 1) continue;
    const std::vector<int> v(vs.begin(), vs.end());
    std::vector<int> pick(D);
    std::function<void(int, int)> rec = [&](int from, int depth) {
      if (depth == D) {
        Index<D> s;
        std::copy(pick.begin(), pick.end(), s.begin());
        if (!GammaTraits<D>::is_simplex(positions(in, s)) || !seen.insert(s).second) return;
        out.push_back({s, profile(root, v, s)});
        return;
      }
      for (int i = from; i < static_cast<int>(v.size()); ++i) pick[depth] = v[i], rec(i + 1, depth + 1);
    };
    rec(0, 0);
  }
}

// Which degenerate triangles of 3D input a query needs listed (the plane
// has neither kind). hull_discs: the triangles of a planar hull face that
// hold another point of the face inside their circle. Only neighbourhoods
// with a half-space take them in (balls_empty: t = ±1), and a face of m
// points has Θ(m³) of them against O(m) others: the 6 faces of a
// 15×15×15 lattice have 11M, which made γ(0,0) run for minutes.
// sphere_interiors: the triangles of a co-spherical cluster with cluster
// points on both sides of their plane. Every point of the cluster lies on
// its empty sphere S, so from both sides the pencil first meets S: lo = hi
// = t_S, exactly (Pencil::finish), and a union of balls (c1 ≥ 0) holds no
// point only when both balls are S, t0 = t1, i.e. c0 = -c1. A cluster of
// m points has Θ(m³) of them and O(m) on its polytope's faces.
struct Listing {
  bool hull_discs = true;
  bool sphere_interiors = true;
};

// Every simplex with an empty touching ball (c'1 ≥ 0), 2D (no hull discs in
// the plane).
std::vector<Candidate<2>> empty_ball_simplices(const Input<2>& in, Listing) {
  using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, K>;
  using Fb = CGAL::Triangulation_face_base_with_info_2<int, K>;
  using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
  using DT = CGAL::Delaunay_triangulation_2<K, Tds>;
  std::vector<Candidate<2>> out;
  Eigen::MatrixX2d P(static_cast<Eigen::Index>(in.P.size()), 2);
  for (std::size_t i = 0; i < in.P.size(); ++i) P.row(static_cast<Eigen::Index>(i)) = in.P[i].transpose();
  if (all_collinear(P)) {  // consecutive points along the line (told first: see all_collinear)
    std::vector<int> order(in.P.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](int a, int b) {
      return std::make_pair(in.P[a].x(), in.P[a].y()) < std::make_pair(in.P[b].x(), in.P[b].y());
    });
    // Each point's neighbours along the line bound the pencil as the
    // opposite vertices of Theorem 3.2 do (every other point lies beyond
    // them on the line): a scan of all points made this quadratic (20k
    // collinear points took 20 s for the Gabriel graph).
    for (std::size_t i = 1; i < order.size(); ++i) {
      const Index<2> s = sorted<2>({order[i - 1], order[i]});
      out.push_back({s, delaunay_profile(in, s, {i >= 2 ? order[i - 2] : -1, i + 1 < order.size() ? order[i + 1] : -1})});
    }
    return out;
  }
  std::vector<std::pair<K::Point_2, int>> pts;
  for (int i = 0; i < static_cast<int>(in.P.size()); ++i) pts.emplace_back(GammaTraits<2>::cg(in.P[i]), i);
  DT dt(pts.begin(), pts.end());
  for (auto e = dt.finite_edges_begin(); e != dt.finite_edges_end(); ++e) {
    const auto f = e->first;
    const int i = e->second;
    const Index<2> s = sorted<2>({f->vertex(DT::cw(i))->info(), f->vertex(DT::ccw(i))->info()});
    const auto opp = f->vertex(i), mir = dt.mirror_vertex(f, i);
    out.push_back({s, delaunay_profile(in, s, {dt.is_infinite(opp) ? -1 : opp->info(),
                                               dt.is_infinite(mir) ? -1 : mir->info()})});
  }
  // Co-circular clusters: every chord of an empty circle has an empty disc.
  Clusters uf;
  std::vector<DT::Face_handle> faces;
  for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f) {
    f->info() = uf.add();
    faces.push_back(f);
  }
  for (const auto f : faces)
    for (int i = 0; i < 3; ++i) {
      const auto g = f->neighbor(i);
      if (dt.is_infinite(g)) continue;
      const auto v = dt.mirror_vertex(f, i);
      if (CGAL::side_of_oriented_circle(f->vertex(0)->point(), f->vertex(1)->point(), f->vertex(2)->point(),
                                        v->point()) == CGAL::ON_ORIENTED_BOUNDARY)
        uf.join(f->info(), g->info());
    }
  const auto groups = cluster_groups(uf, static_cast<int>(faces.size()), [&](int t, std::set<int>& vs) {
    for (int i = 0; i < 3; ++i) vs.insert(faces[static_cast<std::size_t>(t)]->vertex(i)->info());
  });
  if (groups.empty()) return out;
  std::set<Index<2>> seen = simplices_of(out);
  add_cluster_subsets<2>(
      in, groups, [&](int, const std::vector<int>& points, const Index<2>& s) { return profile_among<2>(in, s, points); },
      seen, out);
  return out;
}

// Every simplex with an empty touching ball (c'1 ≥ 0), 3D, but the kinds
// `listing` leaves out (see Listing).
std::vector<Candidate<3>> empty_ball_simplices(const Input<3>& in, Listing listing) {
  using Vb = CGAL::Triangulation_vertex_base_with_info_3<int, K>;
  using Cb = CGAL::Triangulation_cell_base_with_info_3<int, K>;
  using Tds = CGAL::Triangulation_data_structure_3<Vb, Cb>;
  using DT = CGAL::Delaunay_triangulation_3<K, Tds>;
  std::vector<std::pair<K::Point_3, int>> pts;
  for (int i = 0; i < static_cast<int>(in.P.size()); ++i) pts.emplace_back(GammaTraits<3>::cg(in.P[i]), i);
  DT dt(pts.begin(), pts.end());
  std::vector<Candidate<3>> out;
  if (dt.dimension() < 3) {  // coplanar input: every triple, O(N^4)
    if (in.P.size() > 200)
      throw InvalidInput("gamma graph: 3D input is coplanar (" + std::to_string(in.P.size()) +
                         " points); its graph has Θ(N³) triangles, use the 2D graph instead (limit 200 points)");
    const int n = static_cast<int>(in.P.size());
    for (int a = 0; a < n; ++a)
      for (int b = a + 1; b < n; ++b)
        for (int c = b + 1; c < n; ++c) {
          const Index<3> s{a, b, c};
          if (GammaTraits<3>::is_simplex(positions(in, s))) out.push_back({s, scan_profile(in, s)});
        }
    return out;
  }
  for (auto f = dt.finite_facets_begin(); f != dt.finite_facets_end(); ++f) {
    const auto c = f->first;
    const int i = f->second;
    Index<3> s;
    for (int j = 0, k = 0; j < 4; ++j)
      if (j != i) s[k++] = c->vertex(j)->info();
    s = sorted<3>(s);
    const auto opp = c->vertex(i), mir = dt.mirror_vertex(c, i);
    out.push_back({s, delaunay_profile(in, s, {dt.is_infinite(opp) ? -1 : opp->info(),
                                               dt.is_infinite(mir) ? -1 : mir->info()})});
  }
  // Clusters: finite cells on one empty sphere, hull facets on one circle
  // (`spheres`); hull facets in one plane (`planes`).
  Clusters spheres, planes;
  std::vector<DT::Cell_handle> cells;
  for (auto c = dt.all_cells_begin(); c != dt.all_cells_end(); ++c) {
    c->info() = spheres.add();
    planes.add();
    cells.push_back(c);
  }
  for (const auto c : cells)
    for (int i = 0; i < 4; ++i) {
      const auto g = c->neighbor(i);
      const auto v = dt.mirror_vertex(c, i);
      if (dt.is_infinite(c) != dt.is_infinite(g) || dt.is_infinite(v) || c->vertex(i) == dt.infinite_vertex())
        continue;
      std::array<K::Point_3, 4> p;
      int k = 0;
      for (int j = 0; j < 4; ++j)
        if (!dt.is_infinite(c->vertex(j))) p[k++] = c->vertex(j)->point();
      if (!dt.is_infinite(c)) {
        if (CGAL::side_of_oriented_sphere(p[0], p[1], p[2], p[3], v->point()) == CGAL::ON_ORIENTED_BOUNDARY)
          spheres.join(c->info(), g->info());
      } else if (CGAL::orientation(p[0], p[1], p[2], v->point()) == CGAL::COPLANAR) {
        planes.join(c->info(), g->info());
        if (CGAL::coplanar_side_of_bounded_circle(p[0], p[1], p[2], v->point()) == CGAL::ON_BOUNDARY)
          spheres.join(c->info(), g->info());
      }
    }
  std::set<Index<3>> seen;
  // A group's points and the apexes of the cells across its boundary bound
  // its triangles (see add_cluster_subsets). A group of hull facets on one
  // circle likewise: the circle holds no other point of the plane, so a
  // triangle there is first met, on the inner side, by a sphere through
  // the circle that is empty, hence by the apex of a cell behind the face;
  // the outer side holds no point.
  // hull_discs: uf groups the hull facets of one plane, and every triple
  // not listed yet has another point of its face strictly inside its circle
  // (a triple with none lies on an empty circle of the face: a group of
  // `spheres`, listed before). Such a point is in the open triangle (no
  // graph holds the triangle) or else makes it `disc`, so the face's points
  // are asked only the first; the apexes behind the face bound its pencil.
  const auto add_groups = [&](Clusters& uf, bool hull_discs) {
    const auto groups = cluster_groups(uf, static_cast<int>(cells.size()), [&](int t, std::set<int>& vs) {
      const auto c = cells[static_cast<std::size_t>(t)];
      for (int i = 0; i < 4; ++i)
        if (!dt.is_infinite(c->vertex(i))) vs.insert(c->vertex(i)->info());
    });
    if (groups.empty()) return;
    if (seen.empty()) seen = simplices_of(out);
    std::map<int, std::set<int>> apexes;
    for (const auto c : cells) {
      const int root = uf.find(c->info());
      if (!groups.count(root)) continue;
      for (int i = 0; i < 4; ++i)
        if (const auto g = c->neighbor(i); uf.find(g->info()) != root)
          if (const auto v = dt.mirror_vertex(c, i); !dt.is_infinite(v)) apexes[root].insert(v->info());
    }
    const auto bounding = [&](int root, const std::vector<int>& points) {
      std::vector<int> near = points;
      if (const auto it = apexes.find(root); it != apexes.end())
        near.insert(near.end(), it->second.begin(), it->second.end());
      return near;
    };
    const auto profile = [&](int root, const std::vector<int>& points, const Index<3>& s) {
      if (!hull_discs) return profile_among<3>(in, s, bounding(root, points));
      const auto simplex = positions(in, s);
      Profile pr;
      pr.disc = true;
      // A point in the open triangle lies in its box (compared exactly).
      const Eigen::Vector3d lo = simplex[0].cwiseMin(simplex[1]).cwiseMin(simplex[2]);
      const Eigen::Vector3d hi = simplex[0].cwiseMax(simplex[1]).cwiseMax(simplex[2]);
      for (const int q : points) {
        const Eigen::Vector3d& p = in.P[q];
        if ((p.array() < lo.array()).any() || (p.array() > hi.array()).any()) continue;
        if (std::find(s.begin(), s.end(), q) == s.end() && GammaTraits<3>::in_open_triangle(simplex, p)) {
          pr.blocked = true;
          return pr;
        }
      }
      const Pencil<3> pencil(simplex);
      if (const auto it = apexes.find(root); it != apexes.end())
        for (const int a : it->second) pencil.add(pr, a, in.P[a]);
      pencil.finish(pr, in.P);
      return pr;
    };
    using Profiler = std::function<Profile(int key, const std::vector<int>& points, const Index<3>& s)>;
    const auto add_all = [&](const std::map<int, std::set<int>>& some, const Profiler& profiler) {
      // A group of 4 points in one plane has two facets but only 4 vertices.
      for (auto& [key, vs] : some)
        if (vs.size() == 4) {
          std::vector<int> v(vs.begin(), vs.end());
          for (int skip = 0; skip < 4; ++skip) {
            Index<3> s;
            for (int j = 0, k = 0; j < 4; ++j)
              if (j != skip) s[k++] = v[j];
            if (GammaTraits<3>::is_simplex(positions(in, s)) && seen.insert(s).second)
              out.push_back({s, profiler(key, v, s)});
          }
        }
      add_cluster_subsets<3>(in, some, profiler, seen, out);
    };
    if (!hull_discs && !listing.sphere_interiors) {
      // Of a co-spherical cluster only the triangles on its polytope's faces
      // (see Listing), each face the cluster's boundary facets in one plane
      // (a convex polytope has one face per plane), its points on one circle.
      std::map<int, std::vector<std::pair<std::array<K::Point_3, 3>, std::set<int>>>> faces;
      for (const auto c : cells) {
        const int root = uf.find(c->info());
        if (dt.is_infinite(c) || !groups.count(root)) continue;
        for (int i = 0; i < 4; ++i) {
          if (uf.find(c->neighbor(i)->info()) == root) continue;
          std::array<K::Point_3, 3> p;
          std::array<int, 3> ids;
          for (int j = 0, k = 0; j < 4; ++j)
            if (j != i) p[k] = c->vertex(j)->point(), ids[k++] = c->vertex(j)->info();
          auto& list = faces[root];
          auto face = std::find_if(list.begin(), list.end(), [&](const auto& f) {
            return std::all_of(p.begin(), p.end(), [&](const K::Point_3& q) {
              return CGAL::orientation(f.first[0], f.first[1], f.first[2], q) == CGAL::COPLANAR;
            });
          });
          if (face == list.end()) face = list.insert(list.end(), {p, {}});
          face->second.insert(ids.begin(), ids.end());
        }
      }
      // Each face listed as a group of its own, profiled against its cluster.
      std::map<int, std::set<int>> face_groups;
      std::vector<int> cluster_of;  // by face key
      std::map<int, std::vector<int>> cluster_points;
      for (const auto& [root, list] : faces) {
        cluster_points[root].assign(groups.at(root).begin(), groups.at(root).end());
        for (const auto& face : list) {
          face_groups.emplace(static_cast<int>(cluster_of.size()), face.second);
          cluster_of.push_back(root);
        }
      }
      add_all(face_groups, [&](int key, const std::vector<int>&, const Index<3>& s) {
        const int root = cluster_of[static_cast<std::size_t>(key)];
        return profile(root, cluster_points.at(root), s);
      });
      // The hull groups (infinite cells on one circle) are planar: all of their triangles.
      std::map<int, std::set<int>> hull_groups;
      for (const auto& [root, vs] : groups)
        if (!faces.count(root)) hull_groups.emplace(root, vs);
      add_all(hull_groups, profile);
      return;
    }
    add_all(groups, profile);
  };
  add_groups(spheres, false);
  if (listing.hull_discs) add_groups(planes, true);
  return out;
}

// ---------------------------------------------------------------------------
// Static k-d tree over the distinct points: visits the points of the nodes
// whose bounding box meets every ball of a list, with early exit.

template <int D>
struct Ball {
  typename GammaTraits<D>::Vec centre;
  double radius;
};

// A query region: the intersection of balls and slabs lo < n·x < hi; nodes
// whose box misses it are skipped; children nearer `seed` go first.
template <int D>
struct Region {
  using Vec = typename GammaTraits<D>::Vec;
  struct Slab {
    Vec n;
    double lo, hi;
  };
  std::vector<Ball<D>> balls;
  std::vector<Slab> slabs;
  Vec seed;
};

template <int D>
class KdTree {
 public:
  using Vec = typename GammaTraits<D>::Vec;
  explicit KdTree(const std::vector<Vec>& P) : P_(P), order_(P.size()) {
    std::iota(order_.begin(), order_.end(), 0);
    if (!order_.empty()) build(0, static_cast<int>(order_.size()), 0);
    lo_ = hi_ = P.empty() ? Vec::Zero() : P[0];
    for (const Vec& p : P) lo_ = lo_.cwiseMin(p), hi_ = hi_.cwiseMax(p);
  }
  // Calls visit(i) for every point lying in all `balls` and slabs (up to a
  // relative slack of 1e-9, so a few just outside may come too); stops
  // when visit returns false. Returns false if stopped.
  template <typename Visit>
  bool visit(const Region<D>& region, Visit&& visit) const {
    if (order_.empty()) return true;
    return walk(0, static_cast<int>(order_.size()), 0, lo_, hi_, region, visit);
  }
  /// Whether visit(region, …) would call visit(i): the same filter.
  bool reaches(const Region<D>& region, int i) const { return meets(P_[static_cast<std::size_t>(i)], region); }

 private:
  void build(int lo, int hi, int depth) {
    if (hi - lo <= 8) return;
    const int axis = depth % D, mid = (lo + hi) / 2;
    std::nth_element(order_.begin() + lo, order_.begin() + mid, order_.begin() + hi,
                     [&](int a, int b) { return P_[a][axis] < P_[b][axis]; });
    build(lo, mid, depth + 1);
    build(mid + 1, hi, depth + 1);
  }
  static bool meets(const Vec& lo, const Vec& hi, const Region<D>& region) {
    for (const auto& b : region.balls) {
      const Vec q = b.centre.cwiseMax(lo).cwiseMin(hi);
      if ((q - b.centre).squaredNorm() > b.radius * b.radius * (1 + 1e-9)) return false;
    }
    for (const auto& s : region.slabs) {
      const double c = s.n.dot(0.5 * (lo + hi)), e = s.n.cwiseAbs().dot(0.5 * (hi - lo));
      const double slack = 1e-9 * (std::abs(c) + e + std::abs(s.lo) + std::abs(s.hi));
      if (c + e < s.lo - slack || c - e > s.hi + slack) return false;
    }
    return true;
  }
  // A point as a box of no size: the same slack, so no point the exact
  // tests would count is skipped, and the far ones in a visited leaf do not
  // pay for them (on surface samples most of a leaf lies outside a lens).
  static bool meets(const Vec& p, const Region<D>& region) { return meets(p, p, region); }
  template <typename Visit>
  bool walk(int lo, int hi, int depth, const Vec& blo, const Vec& bhi, const Region<D>& balls,
            Visit& visit) const {
    if (!meets(blo, bhi, balls)) return true;
    if (hi - lo <= 8) {
      for (int k = lo; k < hi; ++k)
        if (meets(P_[order_[k]], balls) && !visit(order_[k])) return false;
      return true;
    }
    const int axis = depth % D, mid = (lo + hi) / 2, m = order_[mid];
    if (meets(P_[m], balls) && !visit(m)) return false;
    Vec left_hi = bhi, right_lo = blo;
    left_hi[axis] = right_lo[axis] = P_[m][axis];
    const bool left_first = balls.seed[axis] < P_[m][axis];
    if (left_first)
      return walk(lo, mid, depth + 1, blo, left_hi, balls, visit) &&
             walk(mid + 1, hi, depth + 1, right_lo, bhi, balls, visit);
    return walk(mid + 1, hi, depth + 1, right_lo, bhi, balls, visit) &&
           walk(lo, mid, depth + 1, blo, left_hi, balls, visit);
  }
  const std::vector<Vec>& P_;
  std::vector<int> order_;
  Vec lo_, hi_;  // bounding box of all points
};

// The vertices that last blocked a query, one per kind of query. The
// candidates come in runs sharing all but one vertex (the triples (a, b, ·)),
// whose neighbourhoods overlap: a vertex that blocked one usually blocks the
// next, and one exact test of it replaces a k-d walk (measured in
// gamma_values' comment, reconstruct/gamma_graph.h). It is tested only if
// the walk would reach it, so the answers are the walk's.
struct Blockers {
  int last[2] = {-1, -1};
};

// Exact profile of s when c'1 < 0 and c'1 ≥ floor, else nullopt.
// Phase 1: is a vertex inside the lens N_γ(floor,floor) = ball(floor) ∩
// ball(-floor)? (k-d nodes must meet both balls.) Then c'1 < floor.
// Phase 2: lo and hi from the vertices in ball(floor) ∪ ball(-floor): when
// c'1 < 0 both a = hi and b = -lo are < |floor| (|c'0| ≤ |c'1| ≤ |floor|),
// so their vertices lie in those balls. Rows with c'1 ≥ 0 are not needed
// here (the Delaunay path has them).
template <int D>
std::optional<Profile> lens_profile(const Input<D>& in, const KdTree<D>& tree,
                                    const std::type_identity_t<Index<D>>& s, double floor, Blockers& blockers) {
  const Pencil<D> pencil(positions(in, s));
  if (!GammaTraits<D>::is_simplex(pencil.s)) return std::nullopt;
  const double f = std::abs(floor);
  const auto own = [&](int i) { return std::find(s.begin(), s.end(), i) != s.end(); };
  Profile pr;
  if (f >= 1) {  // N_γ(-1,-1) is the open simplex: every vertex counts
    for (int i = 0; i < static_cast<int>(in.P.size()); ++i)
      if (!own(i)) pencil.add(pr, i, in.P[i]);
    if (pr.blocked) return std::nullopt;
    pencil.finish(pr, in.P);
    return pr;
  }
  const double R = pencil.r / (1.0 - f), offset = std::sqrt(std::max(0.0, R * R - pencil.r * pencil.r));
  const Ball<D> towards_a{pencil.m + offset * pencil.n, R}, towards_b{pencil.m - offset * pencil.n, R};
  // The lens lies in the smallest ball and in the slab |n·(x-m)| < R - offset.
  const double c = pencil.n.dot(pencil.m), w = R - offset;
  const Region<D> lens{{Ball<D>{pencil.m, pencil.r}, towards_a, towards_b}, {{pencil.n, c - w, c + w}}, pencil.m};
  const auto in_lens = [&](int i) {
    Profile probe;
    pencil.add(probe, i, in.P[i]);
    return probe.blocked || probe.disc || probe.hi < floor || probe.lo > -floor;
  };
  int& last = blockers.last[0];
  if (last >= 0 && !own(last) && tree.reaches(lens, last) && in_lens(last)) return std::nullopt;
  const bool lens_empty = tree.visit(lens, [&](int i) {
    if (own(i) || !in_lens(i)) return true;
    last = i;
    return false;
  });
  if (!lens_empty) return std::nullopt;
  // Shrinking searches: side-A vertices with t_p < τ fill ball(τ) ∩ A, and τ
  // drops to the best hi found so far (side B mirrored), like a nearest
  // neighbour search.
  const auto ball_at = [&](double t) {
    const double Rt = pencil.r / (1.0 - std::abs(t));
    const double off = std::sqrt(std::max(0.0, Rt * Rt - pencil.r * pencil.r));
    return Ball<D>{pencil.m + (t < 0 ? -off : off) * pencil.n, Rt};
  };
  for (int side : {1, -1}) {
    const double inf = std::numeric_limits<double>::infinity();
    Region<D> search{{side > 0 ? towards_a : towards_b}, {{pencil.n, side > 0 ? c : -inf, side > 0 ? inf : c}}, pencil.m};
    tree.visit(search, [&](int i) {
      if (own(i)) return true;
      pencil.add(pr, i, in.P[i]);
      search.balls[0] = ball_at(side > 0 ? std::min(pr.hi, f) : std::max(pr.lo, -f));
      return true;
    });
  }
  pencil.finish(pr, in.P);
  return pr;
}

// Yao-cone screen (2D): pair (a,b) survives unless a vertex q sits in the
// cone of a→b (width ≤ 0.45·α) at distance ≤ |ab|/3.3. Then, with ψ the
// angle qab ≤ α/2 and |aq| ≤ |ab|/3, angle aqb > π - α, i.e. q lies in the
// lens N_γ(floor,floor) = {p : angle apb > π - α}, α = asin(1-|floor|).
// Calls visit(s) for every candidate pair, without storing them (the
// candidates of a large input do not fit in memory).
template <typename Visit>
void for_each_screened(const Input<2>& in, double floor, Visit&& visit) {
  const int n = static_cast<int>(in.P.size());
  const double alpha = std::asin(1.0 - std::abs(floor));
  const int cones = static_cast<int>(std::ceil(2 * kPi / (0.45 * alpha)));
  if (!(alpha > 0) || cones > 512) {
    for (int a = 0; a < n; ++a)
      for (int b = a + 1; b < n; ++b) visit(Index<2>{a, b});
    return;
  }
  const double width = 2 * kPi / cones;
  const auto cone = [&](int a, int b) {
    const Eigen::Vector2d d = in.P[b] - in.P[a];
    return std::min(cones - 1, static_cast<int>((std::atan2(d.y(), d.x()) + kPi) / width));
  };
  std::vector<double> near(static_cast<std::size_t>(n) * cones, std::numeric_limits<double>::infinity());
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b)
      if (a != b) {
        double& d = near[static_cast<std::size_t>(a) * cones + cone(a, b)];
        d = std::min(d, (in.P[b] - in.P[a]).squaredNorm());
      }
  const double factor = 3.3 * 3.3;
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b) {
      const double len2 = (in.P[b] - in.P[a]).squaredNorm();
      if (len2 >= factor * near[static_cast<std::size_t>(a) * cones + cone(a, b)]) continue;
      if (len2 >= factor * near[static_cast<std::size_t>(b) * cones + cone(b, a)]) continue;
      visit(Index<2>{a, b});
    }
}

// 3D: every triple (no screen yet), one at a time.
template <typename Visit>
void for_each_screened(const Input<3>& in, double, Visit&& visit) {
  const int n = static_cast<int>(in.P.size());
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b)
      for (int c = b + 1; c < n; ++c) visit(Index<3>{a, b, c});
}

// All simplices with c'1 ≥ floor and their profiles (exact for c'1 < 0 when
// they come from the lens path: see gamma_values in the header).
template <int D>
std::vector<Candidate<D>> candidates(const Input<D>& in, double floor, Listing listing) {
  std::vector<Candidate<D>> out;
  if (static_cast<int>(in.P.size()) < D) return out;
  for (auto& c : empty_ball_simplices(in, listing)) {
    const auto cp = largest_empty(c.profile);
    if (cp && (*cp)[1] >= floor) out.push_back(c);
  }
  if (floor >= 0) return out;
  const KdTree<D> tree(in.P);
  Blockers blockers;
  for_each_screened(in, floor, [&](const Index<D>& s) {
    const auto pr = lens_profile<D>(in, tree, s, floor, blockers);
    if (!pr) return;
    const auto cp = largest_empty(*pr);
    if (cp && (*cp)[1] < 0 && (*cp)[1] >= floor) out.push_back({s, *pr});
  });
  return out;
}

// Rows of caller indices, ascending within a row, rows sorted.
template <int D>
Eigen::Matrix<int, Eigen::Dynamic, D> to_matrix(const Input<D>& in, std::vector<std::type_identity_t<Index<D>>> rows) {
  for (auto& r : rows)
    for (int& v : r) v = in.id[v];
  std::sort(rows.begin(), rows.end());
  Eigen::Matrix<int, Eigen::Dynamic, D> M(rows.size(), D);
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (int j = 0; j < D; ++j) M(static_cast<Eigen::Index>(i), j) = rows[i][j];
  return M;
}

// γ(c0,c1) with -1 < c1 < 0 for a simplex with no empty ball (Definition
// 3.1 directly): it belongs when one of its two neighbourhoods B(t0) ∩ B(t1)
// holds no vertex. Each is one k-d query that stops at the first vertex
// inside; only the vertices the query meets are tested (exactly, as a
// profile of one vertex). Unlike lens_profile, no search for the profile's
// lo and hi: that is what Definition 3.3's values need, not a fixed graph.
template <int D>
bool lens_neighborhood_empty(const Input<D>& in, const KdTree<D>& tree, const std::type_identity_t<Index<D>>& s,
                             double c0, double c1, Blockers& blockers) {
  const Pencil<D> pencil(positions(in, s));
  if (!GammaTraits<D>::is_simplex(pencil.s)) return false;
  const auto own = [&](int i) { return std::find(s.begin(), s.end(), i) != s.end(); };
  const auto ball_at = [&](double t) {
    const double R = pencil.r / (1.0 - std::abs(t));
    const double off = std::sqrt(std::max(0.0, R * R - pencil.r * pencil.r));
    return Ball<D>{pencil.m + (t < 0 ? -off : off) * pencil.n, R};
  };
  int* last = blockers.last;
  for (const auto& [t0, t1] : {std::pair{-c0, c1}, std::pair{c0, -c1}}) {
    const Region<D> region{{ball_at(t0), ball_at(t1)}, {}, pencil.m};
    const auto inside = [&](int i) {
      Profile one;
      pencil.add(one, i, in.P[i]);
      return !balls_empty(one, t0, t1, true);
    };
    int& blocker = *last++;
    if (blocker >= 0 && !own(blocker) && tree.reaches(region, blocker) && inside(blocker)) continue;
    const bool empty = tree.visit(region, [&](int i) {
      if (own(i) || !inside(i)) return true;
      blocker = i;
      return false;
    });
    if (empty) return true;
  }
  return false;
}

// γ(c0,c1) with -1 < c1 < 0: the simplices with an empty ball from their
// profiles (Theorem 3.2), every other candidate by lens_neighborhood_empty.
template <int D>
std::vector<Index<D>> negative_graph(const Input<D>& in, double c0, double c1) {
  std::vector<Index<D>> rows;
  if (static_cast<int>(in.P.size()) < D) return rows;
  std::vector<Index<D>> with_ball;
  for (const auto& c : empty_ball_simplices(in, Listing{false, true})) {  // |c0| ≤ |c1| < 1: no half-space
    if (neighborhood_empty(c.profile, c0, c1)) rows.push_back(c.s);
    Index<D> key = c.s;
    std::sort(key.begin(), key.end());
    with_ball.push_back(key);
  }
  std::sort(with_ball.begin(), with_ball.end());
  const KdTree<D> tree(in.P);
  Blockers blockers;
  for_each_screened(in, c1, [&](const Index<D>& s) {
    Index<D> key = s;
    std::sort(key.begin(), key.end());
    if (std::binary_search(with_ball.begin(), with_ball.end(), key)) return;
    if (lens_neighborhood_empty<D>(in, tree, s, c0, c1, blockers)) rows.push_back(s);
  });
  return rows;
}

template <int D>
Eigen::Matrix<int, Eigen::Dynamic, D> fixed_graph(const Eigen::Matrix<double, Eigen::Dynamic, D>& V, double c0,
                                                   double c1) {
  check_parameter(c0, "c0");
  check_parameter(c1, "c1");
  if (std::abs(c0) > std::abs(c1))
    throw InvalidInput("gamma graph: γ(c0,c1) needs |c0| ≤ |c1| (Definition 3.1), got c0 = " + std::to_string(c0) +
                       ", c1 = " + std::to_string(c1));
  const Input<D> in = prepare<D>(V);
  if (c1 < 0 && c1 > -1) return to_matrix(in, negative_graph(in, c0, c1));
  std::vector<Index<D>> rows;
  // A hull disc needs both balls half-spaces (c1 ≥ 0) or one (c1 < 0); a
  // sphere interior a lens (c1 < 0) or both balls the same, t0 = t1.
  const Listing listing{(c1 == 1 && std::abs(c0) == 1) || c1 == -1, c1 < 0 || c0 == -c1};
  for (const auto& c : candidates(in, std::min(c1, 0.0), listing))
    if (neighborhood_empty(c.profile, c0, c1)) rows.push_back(c.s);
  return to_matrix(in, rows);
}

template <int D>
Eigen::Matrix<int, Eigen::Dynamic, D> range_graph(const Eigen::Matrix<double, Eigen::Dynamic, D>& V,
                                                   const GammaRange& g) {
  check_parameter(g.c0, "c0");
  check_parameter(g.c1, "c1");
  check_parameter(g.c2, "c2");
  check_parameter(g.c3, "c3");
  if (g.c0 > g.c1 || g.c2 > g.c3) throw InvalidInput("gamma graph: empty parameter interval (need c0 ≤ c1, c2 ≤ c3)");
  const Input<D> in = prepare<D>(V);
  std::vector<Index<D>> rows;
  // A hull disc's (c'0, c'1) is (1,1), (-1,1) or (·,-1) (largest_empty).
  const bool discs = (g.c3 == 1 && (g.c0 == -1 || g.c1 == 1)) || g.c2 == -1;
  for (const auto& c : candidates(in, std::min(g.c2, 0.0), Listing{discs, true})) {
    const auto cp = largest_empty(c.profile);
    if (cp && (*cp)[0] >= g.c0 && (*cp)[0] <= g.c1 && (*cp)[1] >= g.c2 && (*cp)[1] <= g.c3) rows.push_back(c.s);
  }
  return to_matrix(in, rows);
}

template <int D>
void values(const Eigen::Matrix<double, Eigen::Dynamic, D>& V, double floor, Eigen::Matrix<int, Eigen::Dynamic, D>& S,
            Eigen::MatrixX2d& C) {
  check_parameter(floor, "floor");
  const Input<D> in = prepare<D>(V);
  std::vector<std::pair<Index<D>, Eigen::Vector2d>> rows;
  for (const auto& c : candidates(in, floor, Listing{})) {
    Index<D> s = c.s;
    for (int& v : s) v = in.id[v];
    rows.emplace_back(s, *largest_empty(c.profile));
  }
  std::sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  S.resize(static_cast<Eigen::Index>(rows.size()), D);
  C.resize(static_cast<Eigen::Index>(rows.size()), 2);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    for (int j = 0; j < D; ++j) S(static_cast<Eigen::Index>(i), j) = rows[i].first[j];
    C.row(static_cast<Eigen::Index>(i)) = rows[i].second.transpose();
  }
}

}  // namespace

Eigen::MatrixX2i gamma_graph(const Eigen::MatrixX2d& V, double c0, double c1) { return fixed_graph<2>(V, c0, c1); }
Eigen::MatrixX3i gamma_graph(const Eigen::MatrixX3d& V, double c0, double c1) { return fixed_graph<3>(V, c0, c1); }
Eigen::MatrixX2i gamma_graph(const Eigen::MatrixX2d& V, const GammaRange& range) { return range_graph<2>(V, range); }
Eigen::MatrixX3i gamma_graph(const Eigen::MatrixX3d& V, const GammaRange& range) { return range_graph<3>(V, range); }

void gamma_values(const Eigen::MatrixX2d& V, double floor, Eigen::MatrixX2i& S, Eigen::MatrixX2d& C) {
  values<2>(V, floor, S, C);
}
void gamma_values(const Eigen::MatrixX3d& V, double floor, Eigen::MatrixX3i& S, Eigen::MatrixX2d& C) {
  values<3>(V, floor, S, C);
}

void gamma_pencil_bounds(const Eigen::MatrixX2d& V, Eigen::MatrixX2i& E, Eigen::MatrixX2d& LH) {
  const Input<2> in = prepare<2>(V);
  std::vector<std::pair<Index<2>, Eigen::Vector2d>> rows;
  if (in.P.size() >= 2)
    for (const auto& c : empty_ball_simplices(in, Listing{})) {
      const auto cp = largest_empty(c.profile);
      if (!cp || (*cp)[1] < 0) continue;
      rows.push_back({{in.id[c.s[0]], in.id[c.s[1]]}, Eigen::Vector2d(c.profile.lo, c.profile.hi)});
    }
  std::sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  E.resize(static_cast<Eigen::Index>(rows.size()), 2);
  LH.resize(static_cast<Eigen::Index>(rows.size()), 2);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    E.row(static_cast<Eigen::Index>(i)) << rows[i].first[0], rows[i].first[1];
    LH.row(static_cast<Eigen::Index>(i)) = rows[i].second.transpose();
  }
}

}  // namespace scanstation
