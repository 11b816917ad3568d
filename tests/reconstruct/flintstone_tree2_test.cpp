// 2D flintstones (thesis §7.2): tree invariants, approximations, exact point
// inclusion against brute force, dynamic insertion (§7.5).
#include "core/errors.h"
#include "reconstruct/flintstone_approximation.h"
#include "reconstruct/flintstone_inclusion.h"
#include "reconstruct/flintstone_tree2.h"
#include "sim/random.h"
#include "test_support.h"

#include <cmath>
#include <numbers>

namespace scanstation {
namespace {

/// A star-shaped (hence simple) polygon with `n` vertices and wiggly radius.
Polygon2 star_polygon(int n, std::uint64_t seed, double scale = 1.0, Eigen::Vector2d offset = {0, 0}) {
  sim::Random random(seed);
  Polygon2 polygon;
  polygon.vertices.resize(n, 2);
  for (int k = 0; k < n; ++k) {
    const double angle = 2.0 * std::numbers::pi * (k + 0.8 * random.uniform()) / n;
    const double radius = 1.0 + 0.3 * std::sin(5.0 * angle) + 0.15 * random.uniform();
    polygon.vertices.row(k) = scale * radius * Eigen::RowVector2d(std::cos(angle), std::sin(angle)) + offset.transpose();
  }
  return polygon;
}

/// The square with extra collinear vertices on every side (degenerate
/// on purpose: many vertices on the chord lines).
Polygon2 square_with_collinear_vertices(int per_side) {
  Polygon2 polygon;
  polygon.vertices.resize(4 * per_side, 2);
  const Eigen::Vector2d corners[] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (int side = 0; side < 4; ++side)
    for (int k = 0; k < per_side; ++k)
      polygon.vertices.row(side * per_side + k) =
          (corners[side] + (corners[(side + 1) % 4] - corners[side]) * k / per_side).transpose();
  return polygon;
}

/// Every vertex of a chain lies in the chain's flintstone (so in every
/// ancestor's), every position appears once, in order, and there are N − 2 nodes.
void expect_valid_tree(const FlintstoneTree2& tree, const std::string& what) {
  const int n = tree.size();
  EXPECT_EQ(tree.live_nodes(), n - 2) << what;
  for (int k = 0; k < n; ++k) EXPECT_TRUE(tree.root.contains(tree.point(k))) << what;
  std::vector<int> in_order;
  std::vector<std::pair<Chain2, int>> stack;  // chain, depth of its node
  const auto tops = tree.top_chains();
  stack.push_back({tops[1], 1});
  stack.push_back({tops[0], 1});
  while (!stack.empty()) {
    const auto [chain, depth] = stack.back();
    stack.pop_back();
    if (chain.node < 0) {
      EXPECT_EQ(chain.s, chain.p + 1) << what;
      in_order.push_back(tree.vertex(chain.p));
      continue;
    }
    const FlintstoneNode2& node = tree.nodes[static_cast<std::size_t>(chain.node)];
    EXPECT_EQ(node.p, chain.p) << what;
    EXPECT_EQ(node.s, chain.s) << what;
    EXPECT_LT(node.p, node.q) << what;
    EXPECT_LT(node.q, node.s) << what;
    EXPECT_EQ(node.depth, depth) << what;
    for (int k = node.p; k <= node.s; ++k)
      EXPECT_TRUE(node.stone.contains(tree.point(k))) << what << ": vertex " << tree.vertex(k) << " outside F";
    EXPECT_FALSE(node.stone.is_union) << what << ": §7.2.2 says 2D flintstones are intersections";
    const auto children = tree.children(node);
    stack.push_back({children[1], depth + 1});
    stack.push_back({children[0], depth + 1});
  }
  ASSERT_EQ(static_cast<int>(in_order.size()), n) << what;
  for (int k = 0; k < n; ++k) EXPECT_EQ(in_order[static_cast<std::size_t>(k)], (tree.first + k) % n) << what;
}

/// Query points: uniform in the box, on and next to vertices and edges.
std::vector<Eigen::Vector2d> queries_near(const Eigen::MatrixX2d& V, int count, std::uint64_t seed) {
  sim::Random random(seed);
  const Eigen::Vector2d lo = V.colwise().minCoeff(), hi = V.colwise().maxCoeff();
  const double size = (hi - lo).norm();
  std::vector<Eigen::Vector2d> queries;
  for (int k = 0; k < count; ++k) {
    const Eigen::Index i = static_cast<Eigen::Index>(random.below(static_cast<std::uint64_t>(V.rows())));
    const Eigen::Vector2d a = V.row(i), b = V.row((i + 1) % V.rows());
    const double t = random.uniform();
    const Eigen::Vector2d jitter(random.normal(), random.normal());
    switch (k % 5) {
      case 0: queries.push_back(lo + (hi - lo).cwiseProduct(Eigen::Vector2d(random.uniform(), random.uniform()))); break;
      case 1: queries.push_back(a); break;
      case 2: queries.push_back(a + t * (b - a)); break;  // on the edge up to rounding
      case 3: queries.push_back(a + t * (b - a) + 1e-12 * size * jitter); break;
      default: queries.push_back(a + t * (b - a) + 1e-3 * size * jitter); break;
    }
  }
  return queries;
}

void expect_inclusion_matches_brute_force(const FlintstoneTree2& tree, int count, std::uint64_t seed,
                                          const std::string& what) {
  int disagreements = 0, inside_count = 0;
  InclusionStats stats;
  for (const Eigen::Vector2d& x : queries_near(tree.vertices, count, seed)) {
    const bool expected = inside_brute_force(tree.vertices, x);
    inside_count += expected;
    disagreements += inside(tree, x, &stats) != expected;
  }
  EXPECT_EQ(disagreements, 0) << what;
  EXPECT_GT(stats.replacements, 0u) << what << ": Lemma 6.1 never used";
  EXPECT_GT(inside_count, count / 10) << what << ": the queries should hit both sides";
  EXPECT_LT(inside_count, count) << what;
}

TEST(FlintstoneTree2, InvariantsOnRandomPolygonsAtAnyScale) {
  for (std::uint64_t seed = 1; seed <= 5; ++seed)
    for (const double scale : {1.0, 1e-8, 1e8}) {
      const Polygon2 polygon = star_polygon(50 + 97 * static_cast<int>(seed), seed, scale, {3e5 * scale, -2.0 * scale});
      const std::string what = "seed " + std::to_string(seed) + " scale " + std::to_string(scale);
      const FlintstoneTree2 tree = flintstone_tree(polygon);
      expect_valid_tree(tree, what);
      expect_inclusion_matches_brute_force(tree, 2000, seed, what);
    }
}

TEST(FlintstoneTree2, DegeneratePolygons) {
  const Polygon2 triangle{(Eigen::MatrixX2d(3, 2) << 0, 0, 1, 0, 0, 1).finished()};
  expect_valid_tree(flintstone_tree(triangle), "triangle");
  const FlintstoneTree2 square = flintstone_tree(square_with_collinear_vertices(7));
  expect_valid_tree(square, "square with collinear vertices");
  expect_inclusion_matches_brute_force(square, 3000, 7, "square with collinear vertices");
  // A polygon that visits a position twice (a pinched boundary).
  const Polygon2 pinched{(Eigen::MatrixX2d(6, 2) << 0, 0, 2, 0, 1, 1, 2, 2, 0, 2, 1, 1).finished()};
  expect_valid_tree(flintstone_tree(pinched), "pinched");
  // Repeated vertices (a scan that dwelt on one point) keep the tree
  // balanced: 20k copies of one corner gave a chain 20k levels deep.
  for (const int copies : {1000, 20000}) {
    Eigen::MatrixX2d dwelt(copies + 2, 2);
    dwelt.topRows(copies).setZero();
    dwelt.bottomRows(2) << 1, 0, 0, 1;
    const FlintstoneTree2 tree = flintstone_tree(Polygon2{dwelt});
    expect_valid_tree(tree, "repeated vertices");
    EXPECT_LE(tree.levels(), 2 * static_cast<int>(std::log2(copies)) + 4) << copies;
    expect_inclusion_matches_brute_force(tree, 500, 3, "repeated vertices");
  }
  test::expect_error<InvalidInput>([] { flintstone_tree(Polygon2{Eigen::MatrixX2d(2, 2)}); }, {"at least 3"});
  test::expect_error<InvalidInput>([] { flintstone_tree(Polygon2{Eigen::MatrixX2d::Ones(4, 2)}); }, {"coincide"});
  // Beyond the balls' range the distinct vertices of a polygon were said to
  // coincide; the message now names the scale.
  const Polygon2 unit{(Eigen::MatrixX2d(3, 2) << 0, 0, 1, 0, 0, 1).finished()};
  test::expect_error<InvalidInput>([&] { flintstone_tree(Polygon2{unit.vertices * 1e300}); },
                                   {"coordinates reach 1e+300", "scale it first"});
  test::expect_error<InvalidInput>([&] { flintstone_tree(Polygon2{unit.vertices * 1e-300}); },
                                   {"spans only 1e-300", "scale it first"});
  test::expect_error<InvalidInput>([&] { flintstone_tree(Polygon2{unit.vertices * 1e100}); }, {"1e+100"});
  expect_valid_tree(flintstone_tree(Polygon2{unit.vertices * 1e60}), "1e60");
  expect_valid_tree(flintstone_tree(Polygon2{unit.vertices * 1e-40}), "1e-40");
}

TEST(FlintstoneApproximation2, LevelsRefineUpToTheOriginal) {
  const Polygon2 polygon = star_polygon(300, 11);
  const FlintstoneTree2 tree = flintstone_tree(polygon);
  EXPECT_EQ(approximation(tree, 0).vertices, (std::vector<int>{tree.first, tree.second}));
  std::size_t previous = 0;
  for (int level = 0; level < tree.levels(); ++level) {
    const PolygonApproximation a = approximation(tree, level);
    EXPECT_GE(a.vertices.size(), previous);
    EXPECT_LE(a.vertices.size(), std::size_t{2} << level);
    EXPECT_LE(a.errors.e2, a.errors.e1 * (1 + 1e-12));  // a line is nearer than its segment
    EXPECT_LE(a.errors.e2, a.errors.e5 * (1 + 1e-6));   // the vertices lie in the flintstones
    previous = a.vertices.size();
  }
  const PolygonApproximation finest = approximation(tree, tree.levels() - 1);
  ASSERT_EQ(finest.vertices.size(), 300u);
  for (int k = 0; k < 300; ++k) EXPECT_EQ(finest.vertices[static_cast<std::size_t>(k)], (tree.first + k) % 300);
  EXPECT_EQ(finest.errors.e1, 0.0);
  EXPECT_EQ(finest.errors.e5, 0.0);
}

TEST(FlintstoneApproximation2, AdaptiveStaysWithinTheBoundWithFewerEdges) {
  const FlintstoneTree2 tree = flintstone_tree(star_polygon(1000, 5));
  for (const double bound : {0.3, 0.05, 0.01, 0.001}) {
    const PolygonApproximation adaptive = adaptive_approximation(tree, bound);
    EXPECT_LE(adaptive.errors.e5, bound);
    // The uniform level that reaches the same depth uses at least as many edges.
    const PolygonApproximation uniform = approximation(tree, adaptive.level);
    EXPECT_LE(adaptive.vertices.size(), uniform.vertices.size()) << bound;
    // e2 of a piece is at most its flintstone width (the vertices lie in it).
    EXPECT_LE(adaptive.errors.e2, adaptive.errors.e5 * (1 + 1e-6) + 1e-12) << bound;
  }
  EXPECT_EQ(adaptive_approximation(tree, 0.0).vertices.size(), 1000u);
}

TEST(FlintstoneTree2, DynamicInsertionKeepsInvariantsAndAnswers) {
  sim::Random random(3);
  FlintstoneTree2 tree = flintstone_tree(star_polygon(200, 3));
  for (int step = 0; step < 60; ++step) {
    const int n = tree.size();
    const int index = static_cast<int>(random.below(static_cast<std::uint64_t>(n)));
    const Eigen::Vector2d a = tree.point(index + n - 1), b = tree.point(index);
    // Mostly close to the boundary, sometimes far out (rebuilds the root).
    const double push = step % 15 == 14 ? 3.0 : 0.05 * random.normal();
    const Eigen::Vector2d x = 0.5 * (a + b) + push * Eigen::Vector2d(-(b - a).y(), (b - a).x()).normalized();
    const int rebuilt = insert_vertex(tree, index, x);
    EXPECT_GE(rebuilt, 1);
    ASSERT_EQ(tree.size(), n + 1);
    EXPECT_EQ(Eigen::Vector2d(tree.vertices.row(index)), x);
    expect_valid_tree(tree, "insertion " + std::to_string(step));
  }
  expect_inclusion_matches_brute_force(tree, 3000, 9, "after insertions");
}

}  // namespace
}  // namespace scanstation
