// Edges by exact length: the same order as a sort by CGAL's exact
// compare_distance, on inputs full of exact ties and near-ties.
#include "reconstruct/edge_length_order.h"
#include "sim/random.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <vector>

namespace scanstation {
namespace {

using K = CGAL::Epick;
using Edge = std::array<int, 2>;

// Every pair of the first n points (i < j), shuffled.
std::vector<Edge> pairs(int n, sim::Random& random) {
  std::vector<Edge> edges;
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) edges.push_back({i, j});
  for (std::size_t k = edges.size(); k > 1; --k)
    std::swap(edges[k - 1], edges[static_cast<std::size_t>(random.uniform(0.0, 1.0) * static_cast<double>(k)) % k]);
  return edges;
}

template <typename Point, typename Compare>
void expect_exact_order(const std::vector<Point>& P, Compare compare_distance, sim::Random& random) {
  std::vector<Edge> edges = pairs(static_cast<int>(P.size()), random);
  std::vector<Edge> reference = edges;
  std::sort(reference.begin(), reference.end(), [&](const Edge& a, const Edge& b) {
    const auto c = compare_distance(P[a[0]], P[a[1]], P[b[0]], P[b[1]]);
    return c == CGAL::SMALLER || (c == CGAL::EQUAL && a < b);
  });
  // Reversed rows as the tie order: the ties must follow `before`, not the input.
  const auto before = [](const Edge& a, const Edge& b) { return Edge{a[1], a[0]} < Edge{b[1], b[0]}; };
  std::vector<Edge> tied_reference = edges;
  std::sort(tied_reference.begin(), tied_reference.end(), [&](const Edge& a, const Edge& b) {
    const auto c = compare_distance(P[a[0]], P[a[1]], P[b[0]], P[b[1]]);
    return c == CGAL::SMALLER || (c == CGAL::EQUAL && before(a, b));
  });
  std::vector<Edge> sorted = edges;
  sort_by_length(sorted, P, std::less<Edge>());
  EXPECT_EQ(sorted, reference);
  sort_by_length(edges, P, before);
  EXPECT_EQ(edges, tied_reference);
}

// Lattices with a binary spacing (every key exact), a decimal one (0.1:
// exact ties and lengths one rounding apart), points one ulp off a lattice,
// huge and tiny coordinates, and a random cloud.
std::vector<std::vector<std::array<double, 3>>> inputs() {
  sim::Random random(11);
  std::vector<std::vector<std::array<double, 3>>> out;
  for (const double h : {0.5, 0.1, 1e-170, 3e150}) {
    std::vector<std::array<double, 3>> lattice;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j)
        for (int k = 0; k < 3; ++k) lattice.push_back({0.3 + h * i, h * j - 7.1 * h, h * k});
    out.push_back(lattice);
  }
  std::vector<std::array<double, 3>> nudged = out[1];
  for (std::size_t i = 0; i < nudged.size(); i += 3) nudged[i][0] = std::nextafter(nudged[i][0], 10.0);
  out.push_back(nudged);
  std::vector<std::array<double, 3>> cloud;
  for (int i = 0; i < 40; ++i) cloud.push_back({random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1)});
  out.push_back(cloud);
  return out;
}

TEST(EdgeLengthOrder, MatchesTheExactComparisonIn2D) {
  sim::Random random(5);
  for (const auto& input : inputs()) {
    std::vector<K::Point_2> P;
    for (const auto& p : input) P.emplace_back(p[0], p[1]);
    expect_exact_order(P, K().compare_distance_2_object(), random);
  }
}

TEST(EdgeLengthOrder, MatchesTheExactComparisonIn3D) {
  sim::Random random(6);
  for (const auto& input : inputs()) {
    std::vector<K::Point_3> P;
    for (const auto& p : input) P.emplace_back(p[0], p[1], p[2]);
    expect_exact_order(P, K().compare_distance_3_object(), random);
  }
}

}  // namespace
}  // namespace scanstation
