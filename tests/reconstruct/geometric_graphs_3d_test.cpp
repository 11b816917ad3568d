// Chapter-2 edge graphs in space: against their definitions by brute force
// (every pair, every other point, exact predicates) on random, lattice,
// co-spherical, duplicated and coplanar points, and the inclusion chain.
#include "reconstruct/geometric_graphs.h"

#include <gtest/gtest.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include "core/errors.h"

namespace scanstation {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Edges = std::vector<std::array<int, 2>>;

Edges edges(const Eigen::MatrixX2i& M) {
  Edges out(static_cast<std::size_t>(M.rows()));
  for (Eigen::Index i = 0; i < M.rows(); ++i) out[static_cast<std::size_t>(i)] = {M(i, 0), M(i, 1)};
  return out;
}

bool subset(const Edges& a, const Edges& b) { return std::includes(b.begin(), b.end(), a.begin(), a.end()); }

// The definitions, over the first occurrences of each position.
struct Brute {
  std::vector<K::Point_3> P;
  std::vector<int> rows;  // first occurrences
  explicit Brute(const Eigen::MatrixX3d& V) {
    for (Eigen::Index i = 0; i < V.rows(); ++i) P.emplace_back(V(i, 0), V(i, 1), V(i, 2));
    for (int i = 0; i < static_cast<int>(P.size()); ++i)
      if (std::none_of(rows.begin(), rows.end(), [&](int r) { return P[r] == P[i]; })) rows.push_back(i);
  }
  Edges pairs_where(const std::function<bool(int, int, int)>& blocks) const {
    Edges out;
    for (std::size_t a = 0; a < rows.size(); ++a)
      for (std::size_t b = a + 1; b < rows.size(); ++b) {
        const int i = rows[a], j = rows[b];
        if (std::none_of(rows.begin(), rows.end(), [&](int k) { return k != i && k != j && blocks(i, j, k); }))
          out.push_back({i, j});
      }
    return out;
  }
  Edges gabriel() const {
    return pairs_where([&](int i, int j, int k) { return K().side_of_bounded_sphere_3_object()(P[i], P[j], P[k]) == CGAL::ON_BOUNDED_SIDE; });
  }
  Edges rng() const {
    const auto cmp = K().compare_distance_3_object();
    return pairs_where([&](int i, int j, int k) {
      return cmp(P[i], P[k], P[i], P[j]) == CGAL::SMALLER && cmp(P[j], P[k], P[j], P[i]) == CGAL::SMALLER;
    });
  }
  bool shorter(const std::array<int, 2>& a, const std::array<int, 2>& b) const {
    const auto c = K().compare_distance_3_object()(P[a[0]], P[a[1]], P[b[0]], P[b[1]]);
    return c == CGAL::SMALLER || (c == CGAL::EQUAL && a < b);
  }
  Edges all_pairs() const { return pairs_where([](int, int, int) { return false; }); }
  Edges emst() const {
    Edges all = all_pairs(), out;
    std::sort(all.begin(), all.end(), [&](const auto& a, const auto& b) { return shorter(a, b); });
    std::vector<int> parent(P.size());
    std::iota(parent.begin(), parent.end(), 0);
    const std::function<int(int)> find = [&](int x) { return parent[x] == x ? x : parent[x] = find(parent[x]); };
    for (const auto& e : all)
      if (find(e[0]) != find(e[1])) parent[find(e[0])] = find(e[1]), out.push_back(e);
    std::sort(out.begin(), out.end());
    return out;
  }
  Edges nng() const {
    Edges out;
    for (int v : rows) {
      std::array<int, 2> best{-1, -1};
      for (const auto& e : all_pairs())
        if ((e[0] == v || e[1] == v) && (best[0] < 0 || shorter(e, best))) best = e;
      if (best[0] >= 0) out.push_back(best);
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }
  Edges cp() const {
    const Edges all = all_pairs();
    Edges out;
    if (all.empty()) return out;
    const auto m = *std::min_element(all.begin(), all.end(), [&](const auto& a, const auto& b) { return shorter(a, b); });
    for (const auto& e : all)
      if (K().compare_distance_3_object()(P[e[0]], P[e[1]], P[m[0]], P[m[1]]) == CGAL::EQUAL) out.push_back(e);
    return out;
  }
};

void expect_matches_brute_force(const Eigen::MatrixX3d& V, const std::string& name) {
  const Brute brute(V);
  EXPECT_EQ(edges(gabriel_graph(V)), brute.gabriel()) << name;
  EXPECT_EQ(edges(relative_neighborhood_graph(V)), brute.rng()) << name;
  EXPECT_EQ(edges(euclidean_minimum_spanning_tree(V)), brute.emst()) << name;
  EXPECT_EQ(edges(nearest_neighbor_graph(V)), brute.nng()) << name;
  EXPECT_EQ(edges(closest_pairs(V)), brute.cp()) << name;
}

Eigen::MatrixX3d lattice(int nx, int ny, int nz) {
  Eigen::MatrixX3d V(nx * ny * nz, 3);
  for (int i = 0; i < V.rows(); ++i) V.row(i) << i % nx, (i / nx) % ny, i / (nx * ny);
  return V;
}

TEST(GeometricGraphs3D, MatchTheDefinitionsOnRandomPoints) {
  for (unsigned seed = 0; seed < 6; ++seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    Eigen::MatrixX3d V(24, 3);
    for (Eigen::Index i = 0; i < V.rows(); ++i) V.row(i) << u(rng), u(rng), u(rng);
    expect_matches_brute_force(V, "seed " + std::to_string(seed));
  }
}

// A lattice is co-spherical and co-circular everywhere: CGAL's
// tetrahedralization picks one diagonal of each square, the Gabriel graph
// has both; ties everywhere decide the EMST and NNG by index.
TEST(GeometricGraphs3D, MatchTheDefinitionsOnDegenerateInput) {
  expect_matches_brute_force(lattice(3, 3, 3), "lattice 3×3×3");
  expect_matches_brute_force(lattice(4, 3, 2), "lattice 4×3×2");
  Eigen::MatrixX3d octahedron(7, 3);  // co-spherical, plus its centre
  octahedron << 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0;
  expect_matches_brute_force(octahedron, "octahedron and centre");
  expect_matches_brute_force(octahedron.topRows(6), "octahedron");
  std::vector<Eigen::RowVector3d> on_sphere;  // the 78 integer points at distance 13 from the origin: one empty sphere
  for (int x = -13; x <= 13; ++x)
    for (int y = -13; y <= 13; ++y)
      for (int z = -13; z <= 13; ++z)
        if (x * x + y * y + z * z == 169) on_sphere.emplace_back(x, y, z);
  Eigen::MatrixX3d sphere(static_cast<Eigen::Index>(on_sphere.size()), 3);
  for (std::size_t k = 0; k < on_sphere.size(); ++k) sphere.row(static_cast<Eigen::Index>(k)) = on_sphere[k];
  expect_matches_brute_force(sphere, "integer points on one sphere");
  Eigen::MatrixX3d hexagon(8, 3);  // a regular hexagon in a plane and two apexes
  for (int k = 0; k < 6; ++k) hexagon.row(k) << std::cos(k * M_PI / 3), std::sin(k * M_PI / 3), 0;
  hexagon.row(6) << 0.1, 0.2, 1.5;
  hexagon.row(7) << -0.2, 0.1, -1.7;
  expect_matches_brute_force(hexagon, "hexagon");
  Eigen::MatrixX3d square(6, 3);  // both diagonals are Gabriel, one is a Delaunay edge
  square << 1, 1, 0, -1, 1, 0, -1, -1, 0, 1, -1, 0, 0.1, 0.2, 2.0, -0.2, 0.1, -2.5;
  expect_matches_brute_force(square, "square and two far apexes");
  // The same square with several points far above and below it: on each
  // side the cells on its two triangles take one apex, so they form one
  // co-spherical cluster however many points there are.
  for (unsigned seed = 0; seed < 4; ++seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    Eigen::MatrixX3d capped(14, 3);
    capped.topRows(4) = square.topRows(4);
    for (int k = 4; k < 14; ++k) capped.row(k) << u(rng), u(rng), (k < 9 ? 3.0 : -3.0) + u(rng);
    expect_matches_brute_force(capped, "square between caps, seed " + std::to_string(seed));
  }
  Eigen::MatrixX3d repeated(30, 3);  // every point three times
  repeated << lattice(2, 5, 1), lattice(2, 5, 1), lattice(2, 5, 1);
  repeated.col(2) += Eigen::VectorXd::LinSpaced(30, 0, 0.0);
  repeated.topRows(10).col(2).setConstant(0.5);
  expect_matches_brute_force(repeated, "duplicates");
  expect_matches_brute_force(lattice(4, 3, 1), "one plane");
  expect_matches_brute_force(lattice(3, 1, 1), "one line");
  expect_matches_brute_force(lattice(2, 1, 1), "two points");
}

TEST(GeometricGraphs3D, InclusionChainAndSpanningTree) {
  std::mt19937 rng(11);
  std::normal_distribution<double> g(0.0, 1.0);
  Eigen::MatrixX3d V(400, 3);  // a noisy sphere, as a scan samples it
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    const Eigen::Vector3d p(g(rng), g(rng), g(rng));
    V.row(i) = (p.normalized() * (1 + 0.01 * g(rng))).transpose();
  }
  const Edges cp = edges(closest_pairs(V)), nng = edges(nearest_neighbor_graph(V)),
              emst = edges(euclidean_minimum_spanning_tree(V)), rng_edges = edges(relative_neighborhood_graph(V)),
              gg = edges(gabriel_graph(V));
  EXPECT_TRUE(subset(cp, nng));
  EXPECT_TRUE(subset(nng, emst));
  EXPECT_TRUE(subset(emst, rng_edges));
  EXPECT_TRUE(subset(rng_edges, gg));
  EXPECT_EQ(emst.size(), 399u);
  EXPECT_GT(gg.size(), rng_edges.size());
}

TEST(GeometricGraphs3D, RejectNonFiniteInputAndLargePlanarSets) {
  Eigen::MatrixX3d V = lattice(3, 3, 3);
  V(4, 1) = std::nan("");
  EXPECT_THROW(gabriel_graph(V), InvalidInput);
  EXPECT_THROW(gabriel_graph(lattice(20, 20, 1)), InvalidInput);
}

}  // namespace
}  // namespace scanstation
