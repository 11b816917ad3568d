// Vertex normals fitted to the nearest vertices (smoothing/fitted_normals.h):
// closer to the true normals than the face normals of §9.4 on a noisy
// sample, on the right side of a thin plate, zero off the surface.
#include "core/errors.h"
#include "sim/random.h"
#include "sim/shapes.h"
#include "smoothing/fitted_normals.h"
#include "smoothing/vertex_normals.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace scanstation {
namespace {

double angle(const Eigen::RowVector3d& a, const Eigen::RowVector3d& b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0));
}

TEST(FittedNormals, FollowANoisySphereCloserThanTheFaceNormals) {
  for (const std::uint64_t seed : {1u, 2u, 3u}) {
    TriangleMesh mesh = sim::icosphere(3);  // 642 vertices on the unit sphere
    sim::Random random(seed);
    for (Eigen::Index v = 0; v < mesh.vertex_count(); ++v)
      mesh.vertices.positions.row(v) *= 1.0 + 0.02 * (2.0 * random.uniform() - 1.0);
    const Eigen::MatrixX3d& V = mesh.vertices.positions;
    const Eigen::MatrixX3d area = vertex_normals(V, mesh.faces, NormalWeighting::area);
    const Eigen::MatrixX3d fitted = fitted_vertex_normals(V, mesh.faces, 16);
    double area_error = 0, fitted_error = 0, worst = 0;
    for (Eigen::Index v = 0; v < V.rows(); ++v) {
      EXPECT_NEAR(fitted.row(v).norm(), 1.0, 1e-12);
      area_error += angle(area.row(v), V.row(v));
      fitted_error += angle(fitted.row(v), V.row(v));
      worst = std::max(worst, angle(fitted.row(v), V.row(v)));
    }
    EXPECT_LT(fitted_error, 0.7 * area_error) << "seed " << seed;
    EXPECT_LT(worst, 10.0 * std::numbers::pi / 180) << "seed " << seed;  // outward everywhere, and close
  }
}

TEST(FittedNormals, FitEachFaceOfAThinWedgeOnItsOwn) {
  // A disc 2 wide and 0.02 thick whose upper face is tilted by atan(0.1),
  // 5.7°: the nearest vertices of a point on the upper face include the
  // lower face's, and a plane through both would lean halfway between them.
  TriangleMesh wedge = sim::ellipsoid({1.0, 1.0, 0.01}, 3);
  Eigen::MatrixX3d& V = wedge.vertices.positions;
  for (Eigen::Index v = 0; v < V.rows(); ++v)
    if (V(v, 2) > 0) V(v, 2) += 0.1 * V(v, 0);
  const Eigen::MatrixX3d N = fitted_vertex_normals(V, wedge.faces, 16);
  const Eigen::RowVector3d upper = Eigen::RowVector3d(-0.1, 0.0, 1.0).normalized();
  int checked = 0;
  for (Eigen::Index v = 0; v < V.rows(); ++v) {
    if (V(v, 2) <= 0 || V.row(v).head<2>().norm() > 0.6) continue;
    ++checked;
    EXPECT_LT(angle(N.row(v), upper), 1.5 * std::numbers::pi / 180) << "vertex " << v;
  }
  EXPECT_GT(checked, 25);
}

TEST(FittedNormals, KeepTheFacesOfAThinPlateApart) {
  // A disc 2 wide and 0.02 thick: the nearest vertices of a point on one face
  // lie on the other face too, whose normals point the other way.
  const TriangleMesh plate = sim::ellipsoid({1.0, 1.0, 0.01}, 3);
  const Eigen::MatrixX3d& V = plate.vertices.positions;
  const Eigen::MatrixX3d N = fitted_vertex_normals(V, plate.faces, 16);
  int faces_checked = 0;
  for (Eigen::Index v = 0; v < V.rows(); ++v) {
    if (V.row(v).head<2>().norm() > 0.8) continue;  // the rim turns
    ++faces_checked;
    EXPECT_GT(N(v, 2) * V(v, 2), 0.0) << "vertex " << v << " points into the plate";
    EXPECT_GT(std::abs(N(v, 2)), std::cos(5.0 * std::numbers::pi / 180)) << "vertex " << v;
  }
  EXPECT_GT(faces_checked, 100);
}

// A scanned bowl seen from the side: a densely sampled wall closed at the
// top by a fan of long hull faces over the unseen inside. The plane fitted
// at a rim vertex is the wall's (its nearest vertices are all on the wall),
// 90° from the lid; the six-split's patches over the lid then folded out
// into flaps 20% of the object's size. The face normals stand there; the
// wall keeps its fitted normals.
TEST(FittedNormals, GiveWayToTheFacesWhereTheyTurnAwayFromThem) {
  constexpr int around = 40, rings = 25;
  TriangleMesh can;
  Eigen::MatrixX3d& V = can.vertices.positions;
  V.resize(around * rings + 2, 3);
  for (int r = 0; r < rings; ++r)
    for (int k = 0; k < around; ++k) {
      const double a = 2 * std::numbers::pi * k / around;
      V.row(r * around + k) << std::cos(a), std::sin(a), 0.04 * r;  // the wall, 0.04 apart
    }
  const int bottom = around * rings, top = bottom + 1;
  V.row(bottom) << 0, 0, 0;
  V.row(top) << 0, 0, 0.04 * (rings - 1);
  std::vector<Eigen::Vector3i> faces;
  for (int r = 0; r + 1 < rings; ++r)
    for (int k = 0; k < around; ++k) {
      const int a = r * around + k, b = r * around + (k + 1) % around;
      faces.emplace_back(a, b, b + around);
      faces.emplace_back(a, b + around, a + around);
    }
  for (int k = 0; k < around; ++k) {
    faces.emplace_back(bottom, (k + 1) % around, k);
    faces.emplace_back(top, (rings - 1) * around + k, (rings - 1) * around + (k + 1) % around);
  }
  can.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f) can.faces.row(static_cast<Eigen::Index>(f)) = faces[f].transpose();
  const Eigen::MatrixX3d area = vertex_normals(V, can.faces, NormalWeighting::area);
  const Eigen::MatrixX3d N = fitted_vertex_normals(V, can.faces, 16);
  for (int k = 0; k < around; ++k) {
    const Eigen::Index rim = (rings - 1) * around + k, wall = (rings / 2) * around + k;
    const Eigen::RowVector3d radial(V(rim, 0), V(rim, 1), 0.0);
    EXPECT_GT(angle(area.row(rim), radial), std::numbers::pi / 4) << k;  // the lid's faces outweigh the wall's
    EXPECT_LT(angle(N.row(rim), area.row(rim)), 1e-12) << k;
    EXPECT_LT(angle(N.row(wall), radial), std::numbers::pi / 180) << k;
  }
}

TEST(FittedNormals, ZeroOffTheSurfaceAndANeighbourCountInRange) {
  TriangleMesh mesh = sim::icosphere(2);
  const Eigen::Index lonely = mesh.vertex_count();
  mesh.vertices.positions.conservativeResize(lonely + 1, 3);
  mesh.vertices.positions.row(lonely) << 0.0, 0.0, 0.5;  // inside, in no face
  const Eigen::MatrixX3d N = fitted_vertex_normals(mesh.vertices.positions, mesh.faces, 8);
  EXPECT_TRUE(N.row(lonely).isZero());
  EXPECT_NEAR(N.row(0).norm(), 1.0, 1e-12);
  EXPECT_THROW(fitted_vertex_normals(mesh.vertices.positions, mesh.faces, 2), InvalidInput);
  EXPECT_THROW(fitted_vertex_normals(mesh.vertices.positions, mesh.faces, static_cast<int>(lonely) + 2), InvalidInput);
}

}  // namespace
}  // namespace scanstation
