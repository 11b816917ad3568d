#include "core/predicates.h"

#include <CGAL/Exact_rational.h>
#include <gtest/gtest.h>

#include <cmath>

namespace scanstation {
namespace {

using Q = CGAL::Exact_rational;

int exact_orientation(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  const Q det = (Q(b.x()) - Q(a.x())) * (Q(c.y()) - Q(a.y())) - (Q(b.y()) - Q(a.y())) * (Q(c.x()) - Q(a.x()));
  return CGAL::sign(det);
}

int naive_orientation(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  const double det = (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
  return (det > 0) - (det < 0);
}

// Points a few ulps around (0.5, 0.5) against a line through (12, 12) and
// (24, 24): floating point gets many of these wrong, the predicate must not.
TEST(Predicates, OrientationIsExactNearDegenerateLines) {
  const double ulp = std::ldexp(1.0, -53);
  const Eigen::Vector2d q(12, 12), r(24, 24);
  int naive_wrong = 0;
  for (int i = 0; i < 64; ++i)
    for (int j = 0; j < 64; ++j) {
      const Eigen::Vector2d p(0.5 + i * ulp, 0.5 + j * ulp);
      const int exact = exact_orientation(p, q, r);
      EXPECT_EQ(orientation(p, q, r), exact) << i << "," << j;
      naive_wrong += naive_orientation(p, q, r) != exact;
    }
  EXPECT_GT(naive_wrong, 0) << "the grid should be hard enough to fool plain doubles";
}

TEST(Predicates, OrientationSignsAndDegenerateCases) {
  const Eigen::Vector3d a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  EXPECT_EQ(orientation(a, b, c, Eigen::Vector3d(0, 0, 1)), -orientation(a, b, c, Eigen::Vector3d(0, 0, -1)));
  EXPECT_NE(orientation(a, b, c, Eigen::Vector3d(0, 0, 1)), 0);
  EXPECT_EQ(orientation(a, b, c, Eigen::Vector3d(0.3, 0.7, 0)), 0);
  EXPECT_EQ(orientation(a, b, c, Eigen::Vector3d(1e-300, 1e-300, 0)), 0);
  EXPECT_NE(orientation(a, b, c, Eigen::Vector3d(0.5, 0.5, 1e-300)), 0);
  EXPECT_EQ(orientation(Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1), Eigen::Vector2d(3, 3)), 0);
  EXPECT_EQ(orientation(Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 0), Eigen::Vector2d(0, 1)), 1);
}

TEST(Predicates, CocircularAndCosphericalPointsAreOnTheBoundary) {
  // Four points of the unit circle with exactly representable coordinates.
  const Eigen::Vector2d a(1, 0), b(0, 1), c(-1, 0), d(0, -1);
  EXPECT_EQ(side_of_oriented_circle(a, b, c, d), 0);
  EXPECT_EQ(side_of_oriented_circle(a, b, c, Eigen::Vector2d(0, 0)), 1);
  EXPECT_EQ(side_of_oriented_circle(a, b, c, Eigen::Vector2d(0, -1 - 1e-15)), -1);
  // The 3-4-5 triple puts (3, 4, 0) exactly on the sphere of radius 5.
  const Eigen::Vector3d p(5, 0, 0), q(0, 5, 0), r(0, 0, 5), s(-5, 0, 0);
  const int positive = orientation(p, q, r, s);
  ASSERT_NE(positive, 0);
  const auto insphere = [&](const Eigen::Vector3d& e) {
    return positive > 0 ? side_of_oriented_sphere(p, q, r, s, e) : side_of_oriented_sphere(p, r, q, s, e);
  };
  EXPECT_EQ(insphere(Eigen::Vector3d(3, 4, 0)), 0);
  EXPECT_EQ(insphere(Eigen::Vector3d(0, -3, 4)), 0);
  EXPECT_EQ(insphere(Eigen::Vector3d(0, 0, -5)), 0);
  EXPECT_EQ(insphere(Eigen::Vector3d(0.1, 0.2, 0.3)), 1);
  EXPECT_EQ(insphere(Eigen::Vector3d(3, 4, 1e-300)), -1);
  EXPECT_EQ(insphere(Eigen::Vector3d(3, 4 - 1e-15, 0)), 1);
}

TEST(Predicates, AllCoplanarIsExactWithDuplicatesAndCollinearStarts) {
  Eigen::MatrixX3d V(6, 3);
  // A repeated first point and a collinear third before the plane is fixed.
  V << 0, 0, 0, 0, 0, 0, 1, 0, 0, 2, 0, 0, 0.1, 0.3, 0, 7, -3, 0;
  EXPECT_TRUE(all_coplanar(V));
  V(5, 2) = 1e-300;  // the smallest lift is out of the plane, exactly
  EXPECT_FALSE(all_coplanar(V));
  // A tilted plane whose points are exact: z = x + y.
  Eigen::MatrixX3d T(5, 3);
  T << 0, 0, 0, 1, 0, 1, 0, 1, 1, 0.5, 0.25, 0.75, 3, -2, 1;
  EXPECT_TRUE(all_coplanar(T));
  EXPECT_TRUE(all_coplanar(T.topRows(3)));
  EXPECT_TRUE(all_coplanar(Eigen::MatrixX3d::Ones(4, 3)));  // one point four times
  EXPECT_TRUE(collinear({0, 0, 0}, {0.5, 0.25, 0.125}, {2, 1, 0.5}));
  EXPECT_FALSE(collinear({0, 0, 0}, {0.5, 0.25, std::nextafter(0.125, 1.0)}, {2, 1, 0.5}));  // one ulp off
  EXPECT_TRUE(collinear({1, 2, 3}, {1, 2, 3}, {5, 5, 5}));  // two equal points
}

TEST(Predicates, AllCollinearIsExactWithDuplicates) {
  Eigen::MatrixX2d V(5, 2);
  V << 0.125, 0.375, 0.125, 0.375, 0.25, 0.75, -1, -3, 0.5, 1.5;  // y = 3x exactly, the first point repeated
  EXPECT_TRUE(all_collinear(V));
  V(4, 1) = std::nextafter(1.5, 2.0);  // one ulp off the line
  EXPECT_FALSE(all_collinear(V));
  EXPECT_TRUE(all_collinear(Eigen::MatrixX2d::Ones(3, 2)));  // one point three times
  EXPECT_TRUE(all_collinear(V.topRows(2)));
  Eigen::MatrixX2d W(3, 2);
  W << 0, 0, 1, 1e-300, 2, 0;  // a triangle a hair tall
  EXPECT_FALSE(all_collinear(W));
}

}  // namespace
}  // namespace scanstation
