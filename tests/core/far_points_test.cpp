#include "core/far_points.h"
#include "sim/shapes.h"
#include "test_support.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace scanstation {
namespace {

TEST(FarPoints, NoneOnAnEvenSurfaceAndTheSpikeOnceAVertexFliesOff) {
  const TriangleMesh sphere = sim::icosphere(4);
  EXPECT_TRUE(far_points(sphere.vertices.positions, sphere.faces).empty());
  Eigen::MatrixX3d spiked = sphere.vertices.positions;
  spiked.row(77) *= 1000.0;  // its edges now ~1000 radii, the others ~0.08
  EXPECT_EQ(far_points(spiked, sphere.faces), std::vector<int>({77}));
  // A vertex a little off is far only for a factor below its own ratio,
  // computed here the long way: every vertex's shortest edge from the
  // faces, and their median.
  spiked.row(77) = sphere.vertices.positions.row(77) * 1.5;
  std::vector<double> shortest(static_cast<std::size_t>(spiked.rows()), INFINITY);
  for (Eigen::Index f = 0; f < sphere.faces.rows(); ++f)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        if (i != j) {
          const int a = sphere.faces(f, i), b = sphere.faces(f, j);
          shortest[static_cast<std::size_t>(a)] = std::min(shortest[static_cast<std::size_t>(a)], (spiked.row(a) - spiked.row(b)).norm());
        }
  std::vector<double> sorted = shortest;
  std::sort(sorted.begin(), sorted.end());
  const double ratio = shortest[77] / sorted[sorted.size() / 2];
  ASSERT_GT(ratio, 3.0);
  EXPECT_TRUE(far_points(spiked, sphere.faces).empty());
  EXPECT_TRUE(far_points(spiked, sphere.faces, ratio * 1.01).empty());
  EXPECT_EQ(far_points(spiked, sphere.faces, ratio * 0.99), std::vector<int>({77}));
}

// The same spike at any scale: near 1e±160 every edge length came out 0 or
// infinite, and no point was far.
TEST(FarPoints, TheSameSpikeScaledByAPowerOfTwo) {
  const TriangleMesh sphere = sim::icosphere(3);
  Eigen::MatrixX3d spiked = sphere.vertices.positions;
  spiked.row(12) *= 1000.0;
  for (const int k : {-1000, -560, 560, 1000}) {
    const Eigen::MatrixX3d scaled = spiked * std::ldexp(1.0, k);
    EXPECT_EQ(far_points(scaled, sphere.faces), std::vector<int>({12})) << k;
  }
}

TEST(FarPoints, APointAmongOthersReachedByLongEdgesIsSpikedNotFar) {
  // The sphere's vertices and one more a hundredth of a radius off vertex
  // 5, which the faces reach only with a triangle across the sphere: its
  // shortest boundary edge is long, its nearest point is not.
  const TriangleMesh sphere = sim::icosphere(4);
  const Eigen::Index n = sphere.vertices.positions.rows();
  Eigen::MatrixX3d V(n + 1, 3);
  V.topRows(n) = sphere.vertices.positions;
  V.row(n) = sphere.vertices.positions.row(5) * 1.01;
  Eigen::MatrixX3i faces(sphere.faces.rows() + 1, 3);
  faces.topRows(sphere.faces.rows()) = sphere.faces;
  Eigen::Index a = 0, b = 0;  // vertex 5's antipode and the vertex nearest that
  (V.topRows(n).rowwise() + V.row(5)).rowwise().norm().minCoeff(&a);
  Eigen::VectorXd from_a = (V.topRows(n).rowwise() - V.row(a)).rowwise().norm();
  from_a(a) = INFINITY;
  from_a.minCoeff(&b);
  faces.bottomRows(1) << static_cast<int>(n), static_cast<int>(a), static_cast<int>(b);
  const double factor = 10.0;  // the sphere's median shortest edge is ~0.08, its diameter 2
  const SpikedPoints spiked = spiked_points(V, faces, factor);
  EXPECT_TRUE(spiked.far.empty());
  EXPECT_EQ(spiked.reached, std::vector<int>({static_cast<int>(n)}));
  EXPECT_TRUE(far_points(V, faces, factor).empty());
  // Moved far away, the same vertex is far (a stray reading).
  V.row(n) *= 1000.0;
  EXPECT_EQ(spiked_points(V, faces, factor).far, std::vector<int>({static_cast<int>(n)}));
  EXPECT_TRUE(spiked_points(V, faces, factor).reached.empty());
}

TEST(FarPoints, APolygonIsOneCycleOfItsVertices) {
  constexpr int n = 60;
  Eigen::MatrixX2d circle(n, 2);
  for (int i = 0; i < n; ++i) circle.row(i) << std::cos(2 * std::numbers::pi * i / n), std::sin(2 * std::numbers::pi * i / n);
  circle.row(40) << 500.0, 0.0;
  Eigen::RowVectorXi order(n);
  for (int i = 0; i < n; ++i) order(i) = i;
  EXPECT_EQ(far_points(circle, order), std::vector<int>({40}));
}

TEST(FarPoints, DegenerateInputsGiveNone) {
  Eigen::MatrixX3d same = Eigen::MatrixX3d::Ones(5, 3);
  Eigen::MatrixXi faces(2, 3);
  faces << 0, 1, 2, 2, 3, 4;
  EXPECT_TRUE(far_points(same, faces).empty());  // every edge has length 0
  EXPECT_TRUE(far_points(same, Eigen::MatrixXi(0, 3)).empty());
  Eigen::MatrixX3d two(2, 3);
  two << 0, 0, 0, 1e9, 0, 0;
  Eigen::MatrixXi edge(1, 2);
  edge << 0, 1;
  EXPECT_TRUE(far_points(two, edge).empty());  // fewer than 3 points on edges: no median to speak of
}

}  // namespace
}  // namespace scanstation
