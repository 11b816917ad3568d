#include "sim/random.h"

#include <gtest/gtest.h>

#include <cmath>

namespace scanstation::sim {
namespace {

// The polar pairs are standard normals: moments and tail shares of 10^6
// pairs, both outputs, and the two outputs of a pair uncorrelated. The
// bounds are about five standard errors, so a wrong scale (e.g. a missing
// factor of √2), a shifted mean or coupled outputs fail.
TEST(Random, NormalPairsAreIndependentStandardNormals) {
  Random random(2026);
  constexpr int n = 1'000'000;
  double sum[2] = {0, 0}, squares[2] = {0, 0}, product = 0, fourth = 0;
  int beyond_two = 0, beyond_four = 0;
  for (int i = 0; i < n; ++i) {
    const auto [x, y] = random.normal_pair();
    for (int k = 0; k < 2; ++k) {
      const double z = k == 0 ? x : y;
      sum[k] += z;
      squares[k] += z * z;
      fourth += z * z * z * z;
      beyond_two += std::abs(z) > 2.0;
      beyond_four += std::abs(z) > 4.0;
    }
    product += x * y;
  }
  for (int k = 0; k < 2; ++k) {
    EXPECT_NEAR(sum[k] / n, 0.0, 0.005);
    EXPECT_NEAR(squares[k] / n, 1.0, 0.007);
  }
  EXPECT_NEAR(product / n, 0.0, 0.005);
  EXPECT_NEAR(fourth / (2.0 * n), 3.0, 0.05);  // kurtosis of a normal
  EXPECT_NEAR(beyond_two / (2.0 * n), 0.0455, 0.0008);  // P(|z| > 2)
  EXPECT_NEAR(beyond_four / (2.0 * n), 6.3e-5, 3.5e-5);  // P(|z| > 4)
}

TEST(Random, NormalPairsRepeatForTheSameSeed) {
  Random a(7), b(7), c(8);
  for (int i = 0; i < 100; ++i) {
    const auto p = a.normal_pair(), q = b.normal_pair();
    EXPECT_EQ(p, q);
  }
  EXPECT_NE(Random(7).normal_pair(), c.normal_pair());
}

}  // namespace
}  // namespace scanstation::sim
