#include "core/unique_points.h"
#include "test_support.h"

namespace scanstation {
namespace {

// Against the quadratic definition on random sets full of repeats.
TEST(UniquePoints, MatchesBruteForce) {
  std::mt19937_64 engine(7);
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::Index n = 1 + static_cast<Eigen::Index>(engine() % 60);
    Eigen::MatrixX3d P(n, 3);
    for (Eigen::Index i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c) P(i, c) = static_cast<double>(engine() % 3) - 1.0;  // few distinct values
    if (n > 2) P.row(n - 1) << -0.0, 0.0, -0.0;
    std::vector<Eigen::Index> first, map;
    const Eigen::Index duplicates = unique_points(P, first, map);
    std::vector<Eigen::Index> expected_first;
    for (Eigen::Index i = 0; i < n; ++i) {
      bool seen = false;
      for (Eigen::Index j = 0; j < i && !seen; ++j) seen = (P.row(i).array() == P.row(j).array()).all();
      if (!seen) expected_first.push_back(i);
    }
    EXPECT_EQ(first, expected_first);
    EXPECT_EQ(duplicates, n - static_cast<Eigen::Index>(expected_first.size()));
    for (Eigen::Index i = 0; i < n; ++i)
      EXPECT_TRUE((P.row(first[static_cast<std::size_t>(map[static_cast<std::size_t>(i)])]).array() == P.row(i).array()).all());
  }
}

}  // namespace
}  // namespace scanstation
