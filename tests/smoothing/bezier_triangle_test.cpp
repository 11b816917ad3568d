#include "smoothing/bezier_triangle.h"

#include "sim/random.h"
#include "test_support.h"

#include <Eigen/Geometry>

namespace scanstation {
namespace {

CubicTriangle random_patch(std::uint64_t seed) {
  sim::Random random(seed);
  CubicTriangle patch;
  for (auto& b : patch) b = Eigen::Vector3d(random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1));
  return patch;
}

Barycentric random_point(sim::Random& random) {
  const double u = random.uniform(), v = random.uniform() * (1.0 - u);
  return {u, v, 1.0 - u - v};
}

// The power-form definition P = Σ b_ijk 3!/(i!j!k!) u^i v^j w^k.
Eigen::Vector3d by_definition(const CubicTriangle& patch, const Barycentric& x) {
  const int factorial[4] = {1, 1, 2, 6};
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int i = 0; i <= 3; ++i)
    for (int j = 0; i + j <= 3; ++j) {
      const int k = 3 - i - j;
      sum += patch[control_index(i, j, k)] * (6.0 / (factorial[i] * factorial[j] * factorial[k])) *
             std::pow(x[0], i) * std::pow(x[1], j) * std::pow(x[2], k);
    }
  return sum;
}

TEST(BezierTriangle, ControlOrderAndEvaluationMatchTheDefinition) {
  EXPECT_EQ(control_index(3, 0, 0), 0);
  EXPECT_EQ(control_index(2, 1, 0), 1);
  EXPECT_EQ(control_index(1, 1, 1), 4);
  EXPECT_EQ(control_index(0, 1, 2), 8);
  EXPECT_EQ(control_index(0, 0, 3), 9);
  sim::Random random(5);
  const CubicTriangle patch = random_patch(9);
  for (int trial = 0; trial < 50; ++trial) {
    const Barycentric x = random_point(random);
    EXPECT_NEAR((evaluate(patch, x) - by_definition(patch, x)).norm(), 0.0, 1e-14);
  }
  EXPECT_EQ(evaluate(patch, Barycentric::UnitY()), patch[control_index(0, 3, 0)]);
}

TEST(BezierTriangle, DerivativeMatchesFiniteDifferences) {
  sim::Random random(6);
  const CubicTriangle patch = random_patch(10);
  for (int trial = 0; trial < 20; ++trial) {
    const Barycentric x = random_point(random) * 0.8 + Barycentric::Constant(0.2 / 3);
    const Eigen::Vector3d d(-1.0, 0.3, 0.7);
    const double h = 1e-6;
    const Eigen::Vector3d numeric = (evaluate(patch, x + h * d) - evaluate(patch, x - h * d)) / (2 * h);
    EXPECT_NEAR((directional_derivative(patch, x, d) - numeric).norm(), 0.0, 1e-8);
  }
}

TEST(BezierTriangle, SubpatchIsTheSameSurface) {
  sim::Random random(7);
  const CubicTriangle patch = random_patch(11);
  const Barycentric r0(0.6, 0.2, 0.2), r1(0.1, 0.8, 0.1), r2 = Barycentric::Constant(1.0 / 3);
  const CubicTriangle part = subpatch(patch, r0, r1, r2);
  for (int trial = 0; trial < 30; ++trial) {
    const Barycentric x = random_point(random);
    const Barycentric in_parent = x[0] * r0 + x[1] * r1 + x[2] * r2;
    EXPECT_NEAR((evaluate(part, x) - evaluate(patch, in_parent)).norm(), 0.0, 1e-14);
  }
}

}  // namespace
}  // namespace scanstation
