// Chapter-2 graphs: inclusion chain, brute-force definitions, and their
// places in the γ-graph spectrum (§3.2).
#include "reconstruct/geometric_graphs.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "core/errors.h"
#include "reconstruct/gamma_brute_force.h"
#include "reconstruct/gamma_graph.h"
#include "test_support.h"

namespace scanstation {
namespace {

using Edges = std::vector<std::array<int, 2>>;

Edges edges(const Eigen::MatrixX2i& M) {
  Edges out(M.rows());
  for (Eigen::Index i = 0; i < M.rows(); ++i) out[i] = {M(i, 0), M(i, 1)};
  return out;
}

Eigen::MatrixX2d random_points(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Eigen::MatrixX2d V(n, 2);
  for (int i = 0; i < n; ++i) V.row(i) << u(rng), u(rng);
  return V;
}

bool subset(const Edges& a, const Edges& b) { return std::includes(b.begin(), b.end(), a.begin(), a.end()); }

double dist2(const Eigen::MatrixX2d& V, int i, int j) { return (V.row(i) - V.row(j)).squaredNorm(); }

// Brute-force definitions (random points: no ties).
Edges brute_pairs(const Eigen::MatrixX2d& V, const std::function<bool(int, int, int)>& blocks) {
  Edges out;
  for (int i = 0; i < V.rows(); ++i)
    for (int j = i + 1; j < V.rows(); ++j) {
      bool empty = true;
      for (int k = 0; k < V.rows() && empty; ++k) empty = k == i || k == j || !blocks(i, j, k);
      if (empty) out.push_back({i, j});
    }
  return out;
}
Edges brute_gabriel(const Eigen::MatrixX2d& V) {  // Definition 2.9
  return brute_pairs(V, [&](int i, int j, int k) { return (V.row(k) - V.row(i)).dot(V.row(k) - V.row(j)) < 0; });
}
Edges brute_rng(const Eigen::MatrixX2d& V) {  // Definition 2.8
  return brute_pairs(V, [&](int i, int j, int k) {
    return std::max(dist2(V, i, k), dist2(V, j, k)) < dist2(V, i, j);
  });
}
double prim_length(const Eigen::MatrixX2d& V) {  // Definition 2.5 on the complete graph
  const int n = static_cast<int>(V.rows());
  std::vector<double> best(n, 1e300);
  std::vector<bool> done(n, false);
  best[0] = 0;
  double total = 0;
  for (int it = 0; it < n; ++it) {
    int u = -1;
    for (int v = 0; v < n; ++v)
      if (!done[v] && (u < 0 || best[v] < best[u])) u = v;
    done[u] = true, total += std::sqrt(best[u]);
    for (int v = 0; v < n; ++v) best[v] = std::min(best[v], dist2(V, u, v));
  }
  return total;
}

TEST(GeometricGraphs, InclusionChainCpNngEmstRngGgDt) {
  for (unsigned seed = 0; seed < 20; ++seed) {
    const auto V = random_points(80, seed);
    const Edges cp = edges(closest_pairs(V)), nng = edges(nearest_neighbor_graph(V)),
                emst = edges(euclidean_minimum_spanning_tree(V)), rng = edges(relative_neighborhood_graph(V)),
                gg = edges(gabriel_graph(V)), dt = edges(delaunay_edges(V));
    EXPECT_EQ(cp.size(), 1u);
    EXPECT_EQ(emst.size(), 79u);
    EXPECT_TRUE(subset(cp, nng));
    EXPECT_TRUE(subset(nng, emst));
    EXPECT_TRUE(subset(emst, rng));
    EXPECT_TRUE(subset(rng, gg));
    EXPECT_TRUE(subset(gg, dt));
    EXPECT_LT(rng.size(), gg.size());
  }
}

TEST(GeometricGraphs, MatchBruteForceDefinitions) {
  for (unsigned seed = 0; seed < 10; ++seed) {
    const auto V = random_points(40, seed);
    EXPECT_EQ(edges(gabriel_graph(V)), brute_gabriel(V));
    EXPECT_EQ(edges(relative_neighborhood_graph(V)), brute_rng(V));
    double len = 0;
    for (const auto& e : edges(euclidean_minimum_spanning_tree(V))) len += std::sqrt(dist2(V, e[0], e[1]));
    EXPECT_NEAR(len, prim_length(V), 1e-12);
    for (const auto& e : edges(nearest_neighbor_graph(V))) {
      double nearest0 = 1e300, nearest1 = 1e300;
      for (int k = 0; k < 40; ++k) {
        if (k != e[0]) nearest0 = std::min(nearest0, dist2(V, e[0], k));
        if (k != e[1]) nearest1 = std::min(nearest1, dist2(V, e[1], k));
      }
      EXPECT_TRUE(dist2(V, e[0], e[1]) == nearest0 || dist2(V, e[0], e[1]) == nearest1);
    }
    // Each vertex is in the nearest neighbour graph.
    std::vector<int> degree(40, 0);
    for (const auto& e : edges(nearest_neighbor_graph(V))) ++degree[e[0]], ++degree[e[1]];
    EXPECT_EQ(std::count(degree.begin(), degree.end(), 0), 0);
  }
}

// §3.2 reductions of the γ-graph.
TEST(GeometricGraphs, GammaReductions) {
  for (unsigned seed = 0; seed < 10; ++seed) {
    const auto V = random_points(40, seed);
    EXPECT_EQ(edges(gamma_graph(V, 0, 0)), brute_gabriel(V));                    // γ(0,0) = GG
    EXPECT_EQ(edges(gamma_graph(V, GammaRange{-1, 1, 0, 1})), edges(delaunay_edges(V)));  // = DT
    EXPECT_EQ(edges(gamma_graph(V, -1, 1)), edges(convex_hull_edges(V)));       // = CH
    EXPECT_EQ(edges(gamma_graph(V, 1, -1)), edges(convex_hull_edges(V)));
    for (double c : {-0.7, -0.3, 0.2, 0.6})  // γ(c,c) = β_c, against the brute force
      EXPECT_EQ(edges(beta_skeleton(V, c, BetaNeighborhood::circle)), test::brute_gamma<2>(V, c, c)) << c;
    // DT ⊆ γ([-1,1],[c,1]) for c ≤ 0 (§3.6).
    EXPECT_TRUE(subset(edges(delaunay_edges(V)), edges(gamma_graph(V, GammaRange{-1, 1, -0.4, 1}))));
  }
}

TEST(GeometricGraphs, LuneSkeletonSpecialValues) {
  for (unsigned seed = 0; seed < 8; ++seed) {
    const auto V = random_points(50, seed);
    EXPECT_EQ(edges(beta_skeleton(V, 0, BetaNeighborhood::lune)), edges(gabriel_graph(V)));
    // Just above 1/2 the lune is the relative neighbourhood up to a hair.
    EXPECT_EQ(edges(beta_skeleton(V, 0.5 + 1e-12, BetaNeighborhood::lune)), edges(relative_neighborhood_graph(V)));
    const Edges l3 = edges(beta_skeleton(V, 0.3, BetaNeighborhood::lune)),
                l7 = edges(beta_skeleton(V, 0.7, BetaNeighborhood::lune)),
                strip = edges(beta_skeleton(V, 1, BetaNeighborhood::lune));
    EXPECT_TRUE(subset(l7, l3));
    EXPECT_TRUE(subset(strip, l7));
    EXPECT_FALSE(strip.empty());
    EXPECT_EQ(edges(beta_skeleton(V, -0.4, BetaNeighborhood::lune)),
              edges(beta_skeleton(V, -0.4, BetaNeighborhood::circle)));
  }
}

TEST(GeometricGraphs, AlphaShape) {
  for (unsigned seed = 0; seed < 8; ++seed) {
    const auto V = random_points(60, seed);
    const Edges dt = edges(delaunay_edges(V)), hull = edges(convex_hull_edges(V));
    EXPECT_EQ(edges(alpha_shape_edges(V, 0)), hull);
    EXPECT_EQ(edges(alpha_shape_edges(V, -1e-9)), hull);  // radius 1e9: half-planes
    const Edges mid = edges(alpha_shape_edges(V, -5));    // radius 0.2
    EXPECT_TRUE(subset(mid, dt));
    EXPECT_FALSE(subset(hull, mid));  // long hull edges need bigger discs
    EXPECT_TRUE(edges(alpha_shape_edges(V, -1e9)).empty());  // radius 1e-9: no disc touches two points
  }
}

// Brute force for a > 0: both discs of radius R through i and j, each
// checked against every point.
Edges furthest_alpha_reference(const Eigen::MatrixX2d& V, double R) {
  Edges out;
  for (Eigen::Index i = 0; i < V.rows(); ++i)
    for (Eigen::Index j = i + 1; j < V.rows(); ++j) {
      const Eigen::Vector2d p = V.row(i), q = V.row(j), m = (p + q) / 2, u = (q - p).normalized();
      const double half = (q - p).norm() / 2;
      if (half > R) continue;
      const Eigen::Vector2d normal(-u.y(), u.x());
      for (const double side : {-1.0, 1.0}) {
        const Eigen::Vector2d c = m + side * std::sqrt(R * R - half * half) * normal;
        if (((V.rowwise() - c.transpose()).rowwise().norm().array() <= R * (1 + 1e-12)).all()) {
          out.push_back({static_cast<int>(i), static_cast<int>(j)});
          break;
        }
      }
    }
  return out;
}

TEST(GeometricGraphs, FurthestPointAlphaShapeEqualsBruteForce) {
  for (unsigned seed = 0; seed < 20; ++seed) {
    const auto V = random_points(40, seed);
    for (const double R : {0.6, 0.75, 1.0, 3.0}) {
      EXPECT_EQ(edges(alpha_shape_edges(V, 1.0 / R)), furthest_alpha_reference(V, R)) << seed << " R " << R;
    }
    EXPECT_EQ(edges(alpha_shape_edges(V, 1e-9)), edges(convex_hull_edges(V)));  // radius 1e9: half-planes
    EXPECT_TRUE(edges(alpha_shape_edges(V, 10)).empty());  // radius 0.1 holds no two far points
  }
  test::expect_error<InvalidInput>([] { alpha_shape_edges(random_points(5, 0), NAN); }, {"not a number"});
}

TEST(GeometricGraphs, DegenerateInput) {
  Eigen::MatrixX2d C(12, 2);  // exactly co-circular
  C << 5, 0, 4, 3, 3, 4, 0, 5, -3, 4, -4, 3, -5, 0, -4, -3, -3, -4, 0, -5, 3, -4, 4, -3;
  const Edges gg = edges(gabriel_graph(C));
  for (int i = 0; i < 6; ++i)  // the 6 diameters cross at the centre, all Gabriel
    EXPECT_NE(std::find(gg.begin(), gg.end(), std::array<int, 2>{i, i + 6}), gg.end()) << i;
  EXPECT_EQ(edges(delaunay_edges(C)).size(), 21u);  // one triangulation: 12 + 9 diagonals
  EXPECT_EQ(edges(convex_hull_edges(C)).size(), 12u);
  EXPECT_EQ(edges(euclidean_minimum_spanning_tree(C)).size(), 11u);
  Eigen::MatrixX2d L(5, 2);
  L << 0, 0, 3, 3, 1, 1, 4, 4, 2, 2;
  const Edges chain{{0, 2}, {1, 3}, {1, 4}, {2, 4}};
  EXPECT_EQ(edges(convex_hull_edges(L)), chain);
  EXPECT_EQ(edges(euclidean_minimum_spanning_tree(L)), chain);
  EXPECT_EQ(edges(gabriel_graph(L)), chain);
  EXPECT_EQ(edges(closest_pairs(L)), chain);  // all four at the same distance
  Eigen::MatrixX2d R(6, 2);  // the line again, row 1 repeated last: the copy is left out
  R << L, L.row(1);
  EXPECT_EQ(edges(delaunay_edges(R)), chain);
  EXPECT_EQ(edges(relative_neighborhood_graph(R)), chain);
  EXPECT_EQ(edges(convex_hull_edges(R)), chain);
  Eigen::MatrixX2d D(4, 2);
  D << 0, 0, 1, 0, 0, 0, 0, 1;  // duplicate of row 0 is left out
  EXPECT_EQ(edges(delaunay_edges(D)), (Edges{{0, 1}, {0, 3}, {1, 3}}));
  EXPECT_TRUE(edges(delaunay_edges(Eigen::MatrixX2d::Zero(1, 2))).empty());
}

TEST(GeometricGraphs, InvariantUnderScalingAndTranslation) {
  const auto V = random_points(80, 3);
  const std::vector<Eigen::MatrixX2d> copies{V * 1e-6, V * 1e6, V.array() + 1e6};
  for (const auto& W : copies) {
    EXPECT_EQ(edges(euclidean_minimum_spanning_tree(W)), edges(euclidean_minimum_spanning_tree(V)));
    EXPECT_EQ(edges(relative_neighborhood_graph(W)), edges(relative_neighborhood_graph(V)));
    EXPECT_EQ(edges(gabriel_graph(W)), edges(gabriel_graph(V)));
    EXPECT_EQ(edges(delaunay_edges(W)), edges(delaunay_edges(V)));
  }
  // Exact copies at the ends of the double range, where squared lengths
  // overflow or underflow: the lune skeleton (it was the Gabriel graph
  // there) and the α-shapes, with α scaled along.
  for (const double scale : {0x1p-1000, 0x1p1000}) {
    const Eigen::MatrixX2d W = V * scale;
    for (const double b : {0.3, 0.8, 1.0})
      EXPECT_EQ(edges(beta_skeleton(W, b, BetaNeighborhood::lune)), edges(beta_skeleton(V, b, BetaNeighborhood::lune)))
          << scale << " " << b;
    for (const double a : {-0.5, 0.5, 2.0})
      EXPECT_EQ(edges(alpha_shape_edges(W, a / scale)), edges(alpha_shape_edges(V, a))) << scale << " " << a;
  }
}

}  // namespace
}  // namespace scanstation
