#include "reconstruct/geometric_graphs.h"

#include "core/errors.h"
#include "core/unique_points.h"
#include "reconstruct/delaunay_complex.h"
#include "reconstruct/edge_length_order.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Fuzzy_sphere.h>
#include <CGAL/Kd_tree.h>
#include <CGAL/Search_traits_3.h>
#include <CGAL/Search_traits_adapter.h>
#include <CGAL/property_map.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <map>
#include <numeric>
#include <vector>

namespace scanstation {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using Edge = std::array<int, 2>;  // distinct-point indices, [0] < [1]

// Up to this many points, input that has no tetrahedralization (all in one
// plane, fewer than four) takes every pair as a candidate instead.
constexpr int kAllPairsLimit = 300;

Edge edge(int a, int b) { return {std::min(a, b), std::max(a, b)}; }

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int x) { return parent[x] == x ? x : parent[x] = find(parent[x]); }
  bool join(int a, int b) {
    a = find(a), b = find(b);
    if (a == b) return false;
    parent[a] = b;
    return true;
  }
};

// The distinct points (first occurrences, caller rows in `row`), the pairs
// that may be Gabriel edges, and each point's Delaunay neighbours — whose
// half-spaces alone bound its Voronoi cell, so they decide whether a
// midpoint is nearest to a pair's two ends.
struct Candidates {
  std::vector<Point> P;
  std::vector<int> row;
  std::vector<Edge> pairs;
  std::vector<std::vector<int>> neighbours;
};

// Every pair of points within each group of more than one item (cells
// joined in `groups`; `points_of` lists an item's points).
template <typename PointsOf>
void all_pairs_of_groups(UnionFind& groups, std::size_t items, PointsOf&& points_of, std::vector<Edge>& out) {
  std::vector<int> size(items, 0);
  for (std::size_t i = 0; i < items; ++i) ++size[static_cast<std::size_t>(groups.find(static_cast<int>(i)))];
  std::map<int, std::vector<int>> members;
  for (std::size_t i = 0; i < items; ++i) {
    const int root = groups.find(static_cast<int>(i));
    if (size[static_cast<std::size_t>(root)] < 2) continue;
    for (int v : points_of(i)) members[root].push_back(v);
  }
  for (auto& [root, m] : members) {
    std::sort(m.begin(), m.end());
    m.erase(std::unique(m.begin(), m.end()), m.end());
    for (std::size_t a = 0; a < m.size(); ++a)
      for (std::size_t b = a + 1; b < m.size(); ++b) out.push_back({m[a], m[b]});
  }
}

Candidates candidates(const Eigen::MatrixX3d& V) {
  if (!V.allFinite()) throw InvalidInput("geometric graphs: the point set holds a non-finite coordinate");
  std::vector<Eigen::Index> first, map;
  unique_points(V, first, map);
  Candidates c;
  const int n = static_cast<int>(first.size());
  Eigen::MatrixX3d U(n, 3);
  for (int u = 0; u < n; ++u) {
    U.row(u) = V.row(first[static_cast<std::size_t>(u)]);
    c.P.emplace_back(U(u, 0), U(u, 1), U(u, 2));
    c.row.push_back(static_cast<int>(first[static_cast<std::size_t>(u)]));
  }
  c.neighbours.resize(static_cast<std::size_t>(n));
  const auto every_pair = [&] {
    for (int a = 0; a < n; ++a)
      for (int b = a + 1; b < n; ++b) {
        c.pairs.push_back({a, b});
        c.neighbours[a].push_back(b), c.neighbours[b].push_back(a);
      }
  };
  DelaunayComplex<3> dt;
  try {
    if (n >= 4) dt = delaunay_complex(U);
  } catch (const InvalidInput&) {
    dt = {};
  }
  if (dt.cells.rows() == 0) {
    if (n > kAllPairsLimit)
      throw InvalidInput("geometric graphs: all " + std::to_string(n) +
                         " points lie in one plane; give them with two coordinates for the 2D graph");
    every_pair();
    return c;
  }

  // The tetrahedralization's edges.
  const Eigen::Index cells = dt.cells.rows();
  for (Eigen::Index t = 0; t < cells; ++t)
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b) c.pairs.push_back(edge(dt.cells(t, a), dt.cells(t, b)));
  std::sort(c.pairs.begin(), c.pairs.end());
  c.pairs.erase(std::unique(c.pairs.begin(), c.pairs.end()), c.pairs.end());
  for (const Edge& e : c.pairs) c.neighbours[e[0]].push_back(e[1]), c.neighbours[e[1]].push_back(e[0]);

  // Chords the tetrahedralization chose between: points of one empty sphere
  // (cells across a face whose far vertex is on the cell's circumsphere);
  // any two of them may be Gabriel. That covers co-circular points in a
  // plane too (a square's two diagonals): every triangle they form has the
  // same circumcircle, so the cells on one side of them all take the same
  // apex, share faces through it and have one circumsphere.
  const auto p = [&](Eigen::Index t, int k) { return c.P[static_cast<std::size_t>(dt.cells(t, k))]; };
  UnionFind spheres(static_cast<std::size_t>(cells));
  bool cospherical = false;
  for (Eigen::Index t = 0; t < cells; ++t)
    for (int i = 0; i < 4; ++i) {
      const int u = dt.neighbors(t, i);
      if (u < t) continue;
      int far = 0;
      while (dt.neighbors(u, far) != t) ++far;
      if (K().side_of_oriented_sphere_3_object()(p(t, 0), p(t, 1), p(t, 2), p(t, 3), p(u, far)) ==
          CGAL::ON_ORIENTED_BOUNDARY)
        cospherical |= spheres.join(static_cast<int>(t), u);
    }
  if (cospherical)
    all_pairs_of_groups(
        spheres, static_cast<std::size_t>(cells),
        [&](std::size_t t) {
          return std::array<int, 4>{dt.cells(t, 0), dt.cells(t, 1), dt.cells(t, 2), dt.cells(t, 3)};
        },
        c.pairs);

  std::sort(c.pairs.begin(), c.pairs.end());
  c.pairs.erase(std::unique(c.pairs.begin(), c.pairs.end()), c.pairs.end());
  return c;
}

// Definition 2.9, exactly: the midpoint of ij is nearest to i (no
// neighbour of i strictly inside the sphere with diameter ij).
std::vector<Edge> gabriel_edges(const Candidates& c) {
  std::vector<Edge> out;
  const auto side = K().side_of_bounded_sphere_3_object();
  for (const Edge& e : c.pairs) {
    const Point &a = c.P[e[0]], &b = c.P[e[1]];
    const auto inside = [&](int k) { return k != e[1] && side(a, b, c.P[k]) == CGAL::ON_BOUNDED_SIDE; };
    if (std::none_of(c.neighbours[e[0]].begin(), c.neighbours[e[0]].end(), inside)) out.push_back(e);
  }
  return out;
}

// Strict total order on edges: exact length, then indices (caller rows).
struct ShorterEdge {
  const Candidates& c;
  bool operator()(const Edge& a, const Edge& b) const {
    const auto order = K().compare_distance_3_object()(c.P[a[0]], c.P[a[1]], c.P[b[0]], c.P[b[1]]);
    return order == CGAL::SMALLER || (order == CGAL::EQUAL && rows(a) < rows(b));
  }
  Edge rows(const Edge& e) const { return edge(c.row[e[0]], c.row[e[1]]); }
};

// Caller rows, i < j, sorted and unique.
Eigen::MatrixX2i to_matrix(const Candidates& c, const std::vector<Edge>& edges) {
  std::vector<Edge> rows;
  for (const Edge& e : edges) rows.push_back(edge(c.row[e[0]], c.row[e[1]]));
  std::sort(rows.begin(), rows.end());
  rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
  Eigen::MatrixX2i M(static_cast<Eigen::Index>(rows.size()), 2);
  for (std::size_t i = 0; i < rows.size(); ++i) M.row(static_cast<Eigen::Index>(i)) << rows[i][0], rows[i][1];
  return M;
}

std::vector<Edge> spanning_tree(const Candidates& c) {
  std::vector<Edge> edges = gabriel_edges(c);
  const ShorterEdge shorter{c};
  sort_by_length(edges, c.P, [&](const Edge& a, const Edge& b) { return shorter.rows(a) < shorter.rows(b); });
  UnionFind trees(c.P.size());
  std::vector<Edge> out;
  for (const Edge& e : edges)
    if (trees.join(e[0], e[1])) out.push_back(e);
  return out;
}

}  // namespace

Eigen::MatrixX2i gabriel_graph(const Eigen::MatrixX3d& V) {
  const Candidates c = candidates(V);
  return to_matrix(c, gabriel_edges(c));
}

Eigen::MatrixX2i relative_neighborhood_graph(const Eigen::MatrixX3d& V) {
  const Candidates c = candidates(V);
  using Traits = CGAL::Search_traits_adapter<int, CGAL::Pointer_property_map<Point>::const_type, CGAL::Search_traits_3<K>>;
  using Tree = CGAL::Kd_tree<Traits>;
  std::vector<int> ids(c.P.size());
  std::iota(ids.begin(), ids.end(), 0);
  const Traits traits(CGAL::make_property_map(c.P));
  Tree tree(ids.begin(), ids.end(), Tree::Splitter(), traits);
  const auto closer = K().compare_distance_3_object();
  std::vector<Edge> out;
  std::vector<int> near;
  for (const Edge& e : gabriel_edges(c)) {
    const Point &a = c.P[e[0]], &b = c.P[e[1]];
    // Every k in the lune has |ak| < |ab|: the ball around a, a little
    // wider than |ab| so that rounding loses none; then the exact test.
    near.clear();
    tree.search(std::back_inserter(near),
                CGAL::Fuzzy_sphere<Traits>(e[0], std::sqrt(CGAL::squared_distance(a, b)) * (1 + 1e-9), 0.0, traits));
    const bool empty = std::none_of(near.begin(), near.end(), [&](int k) {
      return closer(a, c.P[k], a, b) == CGAL::SMALLER && closer(b, c.P[k], b, a) == CGAL::SMALLER;
    });
    if (empty) out.push_back(e);
  }
  return to_matrix(c, out);
}

Eigen::MatrixX2i euclidean_minimum_spanning_tree(const Eigen::MatrixX3d& V) {
  const Candidates c = candidates(V);
  return to_matrix(c, spanning_tree(c));
}

Eigen::MatrixX2i nearest_neighbor_graph(const Eigen::MatrixX3d& V) {
  const Candidates c = candidates(V);  // a nearest neighbour's edge is Gabriel
  std::vector<Edge> best(c.P.size(), Edge{-1, -1});
  const ShorterEdge shorter{c};
  for (const Edge& e : gabriel_edges(c))
    for (int v : e)
      if (best[v][0] < 0 || shorter(e, best[v])) best[v] = e;
  std::vector<Edge> out;
  for (const Edge& e : best)
    if (e[0] >= 0) out.push_back(e);
  return to_matrix(c, out);
}

Eigen::MatrixX2i closest_pairs(const Eigen::MatrixX3d& V) {
  const Candidates c = candidates(V);
  const std::vector<Edge> edges = gabriel_edges(c);
  if (edges.empty()) return Eigen::MatrixX2i(0, 2);
  const Edge shortest = *std::min_element(edges.begin(), edges.end(), ShorterEdge{c});
  const auto compare = K().compare_distance_3_object();
  std::vector<Edge> out;
  for (const Edge& e : edges)
    if (compare(c.P[e[0]], c.P[e[1]], c.P[shortest[0]], c.P[shortest[1]]) == CGAL::EQUAL) out.push_back(e);
  return to_matrix(c, out);
}

}  // namespace scanstation
