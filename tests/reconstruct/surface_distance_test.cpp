// Distances to a triangulated surface (CGAL AABB tree) against a brute-force
// point–triangle distance, and against the exact distance to a polyhedron.
#include "core/errors.h"
#include "reconstruct/surface_distance.h"
#include "sim/random.h"
#include "sim/shapes.h"

#include <Eigen/Geometry>

#include <gtest/gtest.h>

namespace scanstation {
namespace {

// Closest point of triangle abc to p by minimising over the triangle: the
// interior projection when it falls inside, else the closest edge point.
double brute_force_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                            const Eigen::Vector3d& c) {
  const auto segment = [&](const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
    const double t = std::clamp((p - u).dot(v - u) / (v - u).squaredNorm(), 0.0, 1.0);
    return (p - (u + t * (v - u))).norm();
  };
  double best = std::min({segment(a, b), segment(b, c), segment(c, a)});
  const Eigen::Vector3d n = (b - a).cross(c - a).normalized();
  const Eigen::Vector3d q = p - n * n.dot(p - a);
  const double w0 = (b - q).cross(c - q).dot(n), w1 = (c - q).cross(a - q).dot(n), w2 = (a - q).cross(b - q).dot(n);
  if (w0 >= 0 && w1 >= 0 && w2 >= 0) best = std::min(best, std::abs(n.dot(p - a)));
  return best;
}

TEST(SurfaceDistance, EqualsBruteForceOnRandomPoints) {
  const TriangleMesh mesh = sim::ellipsoid({2.0, 1.0, 0.5}, 2);
  sim::Random random(3);
  Eigen::MatrixX3d points(300, 3);
  for (Eigen::Index i = 0; i < points.rows(); ++i)
    points.row(i) << random.uniform(-3, 3), random.uniform(-2, 2), random.uniform(-1, 1);
  const Eigen::VectorXd d = distances_to_surface(points, mesh);
  const auto& V = mesh.vertices.positions;
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    double best = std::numeric_limits<double>::infinity();
    for (Eigen::Index f = 0; f < mesh.face_count(); ++f)
      best = std::min(best, brute_force_distance(points.row(i), V.row(mesh.faces(f, 0)), V.row(mesh.faces(f, 1)),
                                                 V.row(mesh.faces(f, 2))));
    EXPECT_NEAR(d(i), best, 1e-12) << i;
  }
}

TEST(SurfaceDeviation, OfAScaledCopyIsTheScaleDifference) {
  const TriangleMesh truth = sim::icosahedron();
  TriangleMesh bigger = truth;
  bigger.vertices.positions *= 1.1;
  const SurfaceDeviation dev = surface_deviation(bigger, truth);
  // The far vertices of the bigger icosahedron lie 0.1 × circumradius out.
  EXPECT_NEAR(dev.to_truth.max, 0.1 * truth.vertices.positions.row(0).norm(), 1e-12);
  EXPECT_GT(dev.from_truth.max, 0.0);
  EXPECT_LT(dev.from_truth.max, dev.to_truth.max);
  EXPECT_DOUBLE_EQ(dev.hausdorff(), dev.to_truth.max);
  const SurfaceDeviation same = surface_deviation(truth, truth);
  EXPECT_LT(same.hausdorff(), 1e-12);
  EXPECT_THROW(distances_to_surface(Eigen::MatrixX3d::Zero(1, 3), TriangleMesh{}), InvalidInput);
  Eigen::MatrixX3d nan = Eigen::MatrixX3d::Zero(1, 3);
  nan(0, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(distances_to_surface(nan, truth), InvalidInput);
}

}  // namespace
}  // namespace scanstation
