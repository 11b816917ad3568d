// The γ-indicators of Definitions 5.1 and 5.2 against the definitions
// built the long way: the circumcentre solved for, its radius and side.
#include "reconstruct/gamma_indicator.h"
#include "sim/random.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>

namespace scanstation {
namespace {

using sim::Random;

// Definition 5.1 built the long way: the circumcentre of (a, b, l), its
// radius R, r = |ab|/2, and the side of ab it lies on.
double gamma_by_circumcentre(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& l) {
  Eigen::Matrix2d m;
  m << (b - a).transpose(), (l - a).transpose();
  const Eigen::Vector2d rhs(0.5 * (b - a).squaredNorm(), 0.5 * (l - a).squaredNorm());
  const Eigen::Vector2d centre = a + m.fullPivLu().solve(rhs);
  const double ratio = 0.5 * (b - a).norm() / (centre - a).norm();
  const Eigen::Vector2d e = b - a, normal(-e.y(), e.x());
  const double side = normal.dot(l - a) * normal.dot(centre - a);
  return side > 0 ? 1 - ratio : -(1 - ratio);
}

TEST(GammaIndicator2, IsDefinition51OnRandomTriangles) {
  Random random(3);
  for (int trial = 0; trial < 20000; ++trial) {
    const Eigen::Vector2d a(random.uniform(-1, 1), random.uniform(-1, 1)), b(random.uniform(-1, 1), random.uniform(-1, 1)),
        l(random.uniform(-1, 1), random.uniform(-1, 1));
    const double expected = gamma_by_circumcentre(a, b, l);
    if (std::abs(expected) < 1e-9 || !std::isfinite(expected)) continue;
    ASSERT_NEAR(gamma_indicator(a, b, l), expected, 1e-9 * (1 + 1 / (1 - std::abs(expected))));
  }
  // A right angle at l puts the centre on ab: 0. Collinear: no circle, 1.
  EXPECT_EQ(gamma_indicator(Eigen::Vector2d(1, 0), Eigen::Vector2d(0, 1), Eigen::Vector2d(0, 0)), 0.0);
  EXPECT_EQ(gamma_indicator(Eigen::Vector2d(1, 0), Eigen::Vector2d(3, 0), Eigen::Vector2d(2, 0)), 1.0);
  // l far above the edge: near +1; l just above its middle: near −1.
  EXPECT_GT(gamma_indicator(Eigen::Vector2d(-1, 0), Eigen::Vector2d(1, 0), Eigen::Vector2d(0, 1000)), 0.99);
  EXPECT_LT(gamma_indicator(Eigen::Vector2d(-1, 0), Eigen::Vector2d(1, 0), Eigen::Vector2d(0, 0.001)), -0.99);
}

// Definition 5.2 the long way: the tetrahedron's circumcentre from the
// three equations |C − a|² = |C − x|², x = b, c, l; R = |C − a|; r the
// triangle's circumradius; the side of (a, b, c)'s plane C lies on.
double gamma_by_circumcentre(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                             const Eigen::Vector3d& l) {
  Eigen::Matrix3d m;
  m << (b - a).transpose(), (c - a).transpose(), (l - a).transpose();
  const Eigen::Vector3d rhs(0.5 * (b - a).squaredNorm(), 0.5 * (c - a).squaredNorm(), 0.5 * (l - a).squaredNorm());
  const Eigen::Vector3d centre = a + m.fullPivLu().solve(rhs);
  const Eigen::Vector3d e1 = b - a, e2 = c - a, normal = e1.cross(e2);
  const double r = e1.norm() * e2.norm() * (e1 - e2).norm() / (2.0 * normal.norm());
  const double ratio = r / (centre - a).norm();
  const double side = normal.dot(l - a) * normal.dot(centre - a);
  return side > 0 ? 1 - ratio : -(1 - ratio);
}

TEST(GammaIndicator3, IsDefinition52OnRandomTetrahedra) {
  Random random(5);
  const auto point = [&] { return Eigen::Vector3d(random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1)); };
  int compared = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const Eigen::Vector3d a = point(), b = point(), c = point(), l = point();
    const double expected = gamma_by_circumcentre(a, b, c, l);
    if (std::abs(expected) < 1e-9 || !std::isfinite(expected)) continue;
    const double tolerance = 1e-8 * (1 + 1 / (1 - std::abs(expected)));
    ASSERT_NEAR(gamma_indicator(a, b, c, l), expected, tolerance);
    // The triangle's vertex order does not matter.
    ASSERT_NEAR(gamma_indicator(c, b, a, l), expected, tolerance);
    ++compared;
  }
  EXPECT_GT(compared, 19000);
}

TEST(GammaIndicator3, SignAndDegenerateCases) {
  const Eigen::Vector3d a(1, 0, 0), b(-0.5, std::sqrt(3.0) / 2, 0), c(-0.5, -std::sqrt(3.0) / 2, 0);
  // l far above the triangle: near +1; just above its circumcentre: near −1.
  EXPECT_GT(gamma_indicator(a, b, c, Eigen::Vector3d(0, 0, 1000)), 0.99);
  EXPECT_LT(gamma_indicator(a, b, c, Eigen::Vector3d(0, 0, 0.001)), -0.99);
  // On the circle's diametral sphere the centre is in the plane: 0.
  EXPECT_NEAR(gamma_indicator(a, b, c, Eigen::Vector3d(0, 0, 1)), 0.0, 1e-15);
  // A flat tetrahedron and a degenerate triangle have no circumsphere: 1.
  EXPECT_EQ(gamma_indicator(a, b, c, Eigen::Vector3d(0.3, 0.2, 0)), 1.0);
  EXPECT_EQ(gamma_indicator(a, Eigen::Vector3d(2, 0, 0), Eigen::Vector3d(3, 0, 0), Eigen::Vector3d(0, 0, 1)), 1.0);
}

}  // namespace
}  // namespace scanstation
