// PointNeighbours lists a point's Delaunay neighbours when first asked for:
// the lists must equal the vertices sharing a cell with the point, whatever
// order the points are asked in, and a list handed out must stay valid while
// others are computed (augmentation walks two rings with nested loops).
#include "reconstruct/augmentation.h"
#include "reconstruct/delaunay_complex.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>
#include <span>
#include <vector>

namespace scanstation {
namespace {

// Brute force: every vertex that shares a cell with v, sorted.
template <int D>
std::vector<int> shares_a_cell(const DelaunayComplex<D>& dt, int v) {
  std::set<int> out;
  for (Eigen::Index c = 0; c < dt.cells.rows(); ++c) {
    bool has = false;
    for (int i = 0; i <= D; ++i) has = has || dt.cells(c, i) == v;
    if (has)
      for (int i = 0; i <= D; ++i)
        if (dt.cells(c, i) != v) out.insert(dt.cells(c, i));
  }
  return {out.begin(), out.end()};
}

std::vector<int> sorted(std::span<const int> list) {
  std::vector<int> out(list.begin(), list.end());
  std::sort(out.begin(), out.end());
  return out;
}

template <int D>
void expect_neighbours_match(const DelaunayComplex<D>& dt, unsigned seed) {
  const PointNeighbours neighbours(dt);
  const auto n = static_cast<int>(dt.points.rows());
  std::vector<int> order(static_cast<std::size_t>(n));
  for (int v = 0; v < n; ++v) order[static_cast<std::size_t>(v)] = v;
  std::shuffle(order.begin(), order.end(), std::mt19937(seed));
  for (const int v : order) {
    const std::span<const int> list = neighbours[static_cast<std::size_t>(v)];
    const std::vector<int> before(list.begin(), list.end());
    // Nested requests, as in augmentation's two rings, leave `list` intact.
    for (const int u : list) {
      const std::vector<int> expected = shares_a_cell(dt, u);
      EXPECT_EQ(sorted(neighbours[static_cast<std::size_t>(u)]), expected) << "point " << u;
    }
    EXPECT_TRUE(std::equal(list.begin(), list.end(), before.begin(), before.end())) << "point " << v;
    EXPECT_EQ(sorted(list), shares_a_cell(dt, v)) << "point " << v;
    EXPECT_EQ(std::set<int>(list.begin(), list.end()).size(), list.size()) << "point " << v << ": a neighbour twice";
  }
}

TEST(PointNeighbours, EqualTheVerticesSharingACellIn2D) {
  std::mt19937 random(5);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Eigen::MatrixX2d P(60, 2);
  for (Eigen::Index i = 0; i < P.rows(); ++i) P.row(i) << uniform(random), uniform(random);
  expect_neighbours_match(delaunay_complex(P), 1);
  // A lattice: co-circular points everywhere, CGAL's choice of diagonals.
  Eigen::MatrixX2d grid(49, 2);
  for (int i = 0; i < 49; ++i) grid.row(i) << i % 7, i / 7;
  expect_neighbours_match(delaunay_complex(grid), 2);
}

TEST(PointNeighbours, EqualTheVerticesSharingACellIn3D) {
  std::mt19937 random(7);
  std::normal_distribution<double> normal;
  Eigen::MatrixX3d P(80, 3);
  for (Eigen::Index i = 0; i < P.rows(); ++i) P.row(i) = Eigen::RowVector3d(normal(random), normal(random), normal(random));
  expect_neighbours_match(delaunay_complex(P), 3);
  Eigen::MatrixX3d grid(64, 3);
  for (int i = 0; i < 64; ++i) grid.row(i) << i % 4, (i / 4) % 4, i / 16;
  expect_neighbours_match(delaunay_complex(grid), 4);
}

}  // namespace
}  // namespace scanstation
