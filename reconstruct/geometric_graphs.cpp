#include "reconstruct/geometric_graphs.h"

#include "core/predicates.h"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Fuzzy_sphere.h>
#include <CGAL/Kd_tree.h>
#include <CGAL/Search_traits_2.h>
#include <CGAL/Search_traits_adapter.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/property_map.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <numbers>
#include <numeric>
#include <string>
#include <vector>

#include "core/errors.h"
#include "core/unique_points.h"
#include "core/unit_scale.h"
#include "reconstruct/edge_length_order.h"
#include "reconstruct/gamma_graph.h"

namespace scanstation {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Edge = std::array<int, 2>;

// Distinct points and the Delaunay edges between them, in caller indices.
struct Delaunay {
  std::vector<K::Point_2> P;  // indexed by caller row; only `rows` are used
  std::vector<int> rows;      // first occurrences
  std::vector<Edge> edges;    // i < j, caller rows
  std::vector<Edge> hull;     // edges on the convex hull
};

Delaunay delaunay(const Eigen::MatrixX2d& V) {
  if (!V.allFinite()) throw InvalidInput("geometric graphs: the point set holds a non-finite coordinate");
  Eigen::MatrixX3d V3 = Eigen::MatrixX3d::Zero(V.rows(), 3);
  V3.leftCols(2) = V;
  std::vector<Eigen::Index> first, map;
  unique_points(V3, first, map);
  Delaunay d;
  for (Eigen::Index i = 0; i < V.rows(); ++i) d.P.emplace_back(V(i, 0), V(i, 1));
  using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, K>;
  using DT = CGAL::Delaunay_triangulation_2<K, CGAL::Triangulation_data_structure_2<Vb>>;
  std::vector<std::pair<K::Point_2, int>> pts;
  for (Eigen::Index f : first) d.rows.push_back(static_cast<int>(f)), pts.emplace_back(d.P[f], static_cast<int>(f));
  const auto edge = [](int a, int b) { return Edge{std::min(a, b), std::max(a, b)}; };
  if (all_collinear(V)) {  // consecutive points along the line, all on the hull (see all_collinear)
    std::sort(pts.begin(), pts.end());
    for (std::size_t i = 1; i < pts.size(); ++i) d.edges.push_back(edge(pts[i - 1].second, pts[i].second));
    std::sort(d.edges.begin(), d.edges.end());
    d.hull = d.edges;
    return d;
  }
  DT dt(pts.begin(), pts.end());
  for (auto e = dt.finite_edges_begin(); e != dt.finite_edges_end(); ++e) {
    const auto f = e->first;
    const int i = e->second;
    const Edge ij = edge(f->vertex(DT::cw(i))->info(), f->vertex(DT::ccw(i))->info());
    d.edges.push_back(ij);
    if (dt.dimension() < 2 || dt.is_infinite(f) || dt.is_infinite(dt.mirror_vertex(f, i))) d.hull.push_back(ij);
  }
  std::sort(d.edges.begin(), d.edges.end());
  std::sort(d.hull.begin(), d.hull.end());
  return d;
}

Eigen::MatrixX2i to_matrix(std::vector<Edge> E) {
  std::sort(E.begin(), E.end());
  E.erase(std::unique(E.begin(), E.end()), E.end());
  Eigen::MatrixX2i M(E.size(), 2);
  for (std::size_t i = 0; i < E.size(); ++i) M.row(static_cast<Eigen::Index>(i)) << E[i][0], E[i][1];
  return M;
}

// Strict total order on edges: exact length, then indices.
struct ShorterEdge {
  const std::vector<K::Point_2>& P;
  bool operator()(const Edge& a, const Edge& b) const {
    const auto c = K().compare_distance_2_object()(P[a[0]], P[a[1]], P[b[0]], P[b[1]]);
    return c == CGAL::SMALLER || (c == CGAL::EQUAL && a < b);
  }
};

int find(std::vector<int>& parent, int x) { return parent[x] == x ? x : parent[x] = find(parent, parent[x]); }

// The distinct points within a disc, from a k-d tree over them: a disc a
// little wider than asked, so that rounding loses none; callers then decide
// exactly (or by their own test) on what it returns.
class PointsNear {
 public:
  explicit PointsNear(const Delaunay& d)
      : traits_(CGAL::make_property_map(d.P)), tree_(d.rows.begin(), d.rows.end(), Tree::Splitter(), traits_) {}
  const std::vector<int>& operator()(const K::Point_2& centre, double radius) {
    found_.clear();
    tree_.search(std::back_inserter(found_), CGAL::Fuzzy_sphere<Traits>(centre, radius * (1 + 1e-9), 0.0, traits_));
    return found_;
  }

 private:
  using Traits = CGAL::Search_traits_adapter<int, CGAL::Pointer_property_map<K::Point_2>::const_type,
                                             CGAL::Search_traits_2<K>>;
  using Tree = CGAL::Kd_tree<Traits>;
  Traits traits_;
  Tree tree_;
  std::vector<int> found_;
};

}  // namespace

Eigen::MatrixX2i delaunay_edges(const Eigen::MatrixX2d& V) { return to_matrix(delaunay(V).edges); }

Eigen::MatrixX2i convex_hull_edges(const Eigen::MatrixX2d& V) { return to_matrix(delaunay(V).hull); }

Eigen::MatrixX2i gabriel_graph(const Eigen::MatrixX2d& V) {
  // Candidates: every edge with an empty disc (Delaunay plus co-circular
  // chords); Gabriel iff the smallest disc (t = 0) is empty: lo ≤ 0 ≤ hi,
  // whose signs are exact predicates (side_of_bounded_circle).
  Eigen::MatrixX2i E;
  Eigen::MatrixX2d LH;
  gamma_pencil_bounds(V, E, LH);
  std::vector<Edge> out;
  for (Eigen::Index i = 0; i < E.rows(); ++i)
    if (LH(i, 0) <= 0 && LH(i, 1) >= 0) out.push_back({E(i, 0), E(i, 1)});
  return to_matrix(out);
}

Eigen::MatrixX2i relative_neighborhood_graph(const Eigen::MatrixX2d& V) {
  const Delaunay d = delaunay(V);
  const Eigen::MatrixX2i G = gabriel_graph(V);  // RNG ⊆ GG
  PointsNear points_near(d);
  const auto cmp = K().compare_distance_2_object();
  std::vector<Edge> out;
  for (Eigen::Index e = 0; e < G.rows(); ++e) {
    const K::Point_2 &a = d.P[G(e, 0)], &b = d.P[G(e, 1)];
    const std::vector<int>& near = points_near(a, std::sqrt(CGAL::squared_distance(a, b)));  // the lune's k: |ak| < |ab|
    const bool empty = std::none_of(near.begin(), near.end(), [&](int k) {
      return cmp(a, d.P[k], a, b) == CGAL::SMALLER && cmp(b, d.P[k], b, a) == CGAL::SMALLER;
    });
    if (empty) out.push_back({G(e, 0), G(e, 1)});
  }
  return to_matrix(out);
}

Eigen::MatrixX2i euclidean_minimum_spanning_tree(const Eigen::MatrixX2d& V) {
  Delaunay d = delaunay(V);
  sort_by_length(d.edges, d.P, std::less<Edge>());  // Kruskal's order: exact length, then rows
  std::vector<int> parent(d.P.size());
  std::iota(parent.begin(), parent.end(), 0);
  std::vector<Edge> out;
  for (const Edge& e : d.edges) {
    const int a = find(parent, e[0]), b = find(parent, e[1]);
    if (a != b) parent[a] = b, out.push_back(e);
  }
  return to_matrix(out);
}

Eigen::MatrixX2i nearest_neighbor_graph(const Eigen::MatrixX2d& V) {
  const Delaunay d = delaunay(V);  // a nearest neighbour is a Delaunay neighbour
  std::vector<Edge> best(d.P.size(), Edge{-1, -1});
  const ShorterEdge shorter{d.P};
  for (const Edge& e : d.edges)
    for (int v : e)
      if (best[v][0] < 0 || shorter(e, best[v])) best[v] = e;
  std::vector<Edge> out;
  for (int v : d.rows)
    if (best[v][0] >= 0) out.push_back(best[v]);
  return to_matrix(out);
}

Eigen::MatrixX2i closest_pairs(const Eigen::MatrixX2d& V) {
  const Delaunay d = delaunay(V);  // a closest pair is a Delaunay edge
  if (d.edges.empty()) return Eigen::MatrixX2i(0, 2);
  const Edge shortest = *std::min_element(d.edges.begin(), d.edges.end(), ShorterEdge{d.P});
  const auto cmp = K().compare_distance_2_object();
  std::vector<Edge> out;
  for (const Edge& e : d.edges)
    if (cmp(d.P[e[0]], d.P[e[1]], d.P[shortest[0]], d.P[shortest[1]]) == CGAL::EQUAL) out.push_back(e);
  return to_matrix(out);
}

namespace {

// α(a)-shape for a > 0 (Definitions 2.12–2.14): edges ij with a disc of radius
// R = 1/a through i and j that holds every point, i.e. the arcs of the
// intersection of the discs of radius R around the points. A disc holds all
// points iff it holds the hull vertices, so only those are visited. For each
// hull vertex i the centres on the circle of radius R around i that are within
// R of vertex k form an arc of half-width acos(|ik|/2R) towards k; all these
// arcs are shorter than π, so their intersection is one arc, and the vertices
// bounding it are i's neighbours in the shape. O(H²) for H hull vertices; the
// angles are double constructions.
Eigen::MatrixX2i furthest_point_alpha_shape_edges(const Eigen::MatrixX2d& V, double R) {
  const Delaunay d = delaunay(V);
  std::vector<int> hull;
  for (const Edge& e : d.hull) hull.insert(hull.end(), e.begin(), e.end());
  std::sort(hull.begin(), hull.end());
  hull.erase(std::unique(hull.begin(), hull.end()), hull.end());
  std::vector<Edge> out;
  const auto angle = [&](int from, int to) { return std::atan2(V(to, 1) - V(from, 1), V(to, 0) - V(from, 0)); };
  for (const int i : hull) {
    struct Arc { int k; double lo, hi; };
    std::vector<Arc> arcs;
    double reference = 0.0, lo = -INFINITY, hi = INFINITY;
    for (const int k : hull) {
      if (k == i) continue;
      const double distance = (V.row(k) - V.row(i)).stableNorm();
      if (distance > 2.0 * R) { lo = INFINITY; break; }  // no disc of radius R holds both
      if (arcs.empty()) reference = angle(i, k);
      const double centre = std::remainder(angle(i, k) - reference, 2.0 * std::numbers::pi);
      const double half_width = std::acos(std::min(1.0, distance / (2.0 * R)));
      arcs.push_back({k, centre - half_width, centre + half_width});
      lo = std::max(lo, centre - half_width);
      hi = std::min(hi, centre + half_width);
    }
    if (arcs.empty() || lo > hi) continue;
    const double tolerance = 1e-12 * std::numbers::pi;  // ties of co-circular points
    for (const Arc& arc : arcs)
      if (arc.lo >= lo - tolerance || arc.hi <= hi + tolerance) out.push_back({std::min(i, arc.k), std::max(i, arc.k)});
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return to_matrix(out);
}

}  // namespace

Eigen::MatrixX2i alpha_shape_edges(const Eigen::MatrixX2d& V, double a) {
  if (std::isnan(a)) throw InvalidInput("alpha_shape_edges: a is not a number");
  if (a > 0) return furthest_point_alpha_shape_edges(V, 1.0 / a);
  if (a == 0) return convex_hull_edges(V);
  Eigen::MatrixX2i E;
  Eigen::MatrixX2d LH;
  gamma_pencil_bounds(V, E, LH);
  std::vector<Edge> out;
  for (Eigen::Index i = 0; i < E.rows(); ++i) {
    const double r = 0.5 * (V.row(E(i, 0)) - V.row(E(i, 1))).stableNorm();  // no overflow at 1e300
    const double t = 1.0 - r * std::abs(a);  // the disc of radius 1/|a| has |t| = 1 - r|a|
    if (t < 0) continue;                     // 1/|a| < r: no such disc
    if ((LH(i, 0) <= t && t <= LH(i, 1)) || (LH(i, 0) <= -t && -t <= LH(i, 1))) out.push_back({E(i, 0), E(i, 1)});
  }
  return to_matrix(out);
}

Eigen::MatrixX2i beta_skeleton(const Eigen::MatrixX2d& input, double b, BetaNeighborhood kind) {
  if (!(b >= -1 && b <= 1)) throw InvalidInput("beta_skeleton: b = " + std::to_string(b) + " lies outside [-1, 1]");
  if (kind == BetaNeighborhood::circle || b <= 0) return gamma_graph(input, b, b);  // N_βc(b) = N_γ(b,b)
  if (b == 0.5) return relative_neighborhood_graph(input);
  // The lune test squares lengths: scaled exactly to magnitudes near 1 it
  // neither overflows at 1e300 nor underflows at 1e-300 (the graph is the same).
  const Eigen::MatrixX2d V = input * unit_scale(input);
  const Delaunay d = delaunay(V);
  const Eigen::MatrixX2i G = gabriel_graph(V);  // the lune holds the Gabriel disc
  PointsNear points_near(d);
  std::vector<Edge> out;
  for (Eigen::Index e = 0; e < G.rows(); ++e) {
    const Eigen::Vector2d p = V.row(G(e, 0)), q = V.row(G(e, 1));
    const double len = (q - p).norm();
    const auto in_lune = [&](const Eigen::Vector2d& x) {
      if (b == 1) return (x - p).dot(q - p) > 0 && (x - q).dot(p - q) > 0;  // infinite strip
      const double R = len / (2 * (1 - b));
      const Eigen::Vector2d cp = p + (q - p) / (2 * (1 - b)), cq = q + (p - q) / (2 * (1 - b));
      return (x - cp).squaredNorm() < R * R && (x - cq).squaredNorm() < R * R;
    };
    // The lune lies in the disc of radius R around cp (b < 1); the strip of
    // b = 1 is unbounded: every point is asked.
    const auto blocks = [&](int k) { return k != G(e, 0) && k != G(e, 1) && in_lune(V.row(k).transpose()); };
    const Eigen::Vector2d centre = p + (q - p) / (2 * (1 - b));
    const bool empty = b == 1 ? std::none_of(d.rows.begin(), d.rows.end(), blocks)
                              : std::ranges::none_of(points_near(K::Point_2(centre.x(), centre.y()), len / (2 * (1 - b))), blocks);
    if (empty) out.push_back({G(e, 0), G(e, 1)});
  }
  return to_matrix(out);
}

}  // namespace scanstation
