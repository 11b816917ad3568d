// Vertices moved onto jets fitted to their neighbours
// (smoothing/jet_fitted_vertices.h): a noisy sphere's vertices come out
// nearer the sphere, a noise-free one's stay, and neither the sharp rims of
// a can nor the two faces of a thin plate are blurred into each other.
#include "core/errors.h"
#include "sim/random.h"
#include "sim/shapes.h"
#include "sim/surface_of_revolution.h"
#include "smoothing/jet_fitted_vertices.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace scanstation {
namespace {

double rms(const Eigen::VectorXd& x) { return std::sqrt(x.squaredNorm() / static_cast<double>(x.size())); }

double mean_edge(const TriangleMesh& mesh) {
  double sum = 0.0;
  for (Eigen::Index f = 0; f < mesh.face_count(); ++f)
    sum += (mesh.vertices.positions.row(mesh.faces(f, 0)) - mesh.vertices.positions.row(mesh.faces(f, 1))).norm();
  return sum / static_cast<double>(mesh.face_count());
}

TEST(JetFittedVertices, BringANoisySphereNearerTheSphere) {
  for (const std::uint64_t seed : {1u, 2u, 3u}) {
    TriangleMesh mesh = sim::icosphere(4);  // 2562 vertices, edges about 0.08
    constexpr double sigma = 0.004;
    sim::Random random(seed);
    for (Eigen::Index v = 0; v < mesh.vertex_count(); ++v)
      mesh.vertices.positions.row(v) *= 1.0 + sigma * random.normal();
    const Eigen::MatrixX3d& V = mesh.vertices.positions;
    const JetFittedVertices fitted = jet_fitted_vertices(V, mesh.faces, 16);
    const Eigen::VectorXd before = (V.rowwise().norm().array() - 1.0).matrix();
    const Eigen::VectorXd after = (fitted.positions.rowwise().norm().array() - 1.0).matrix();
    EXPECT_LT(rms(after), 0.6 * rms(before)) << "seed " << seed;
    EXPECT_GT(fitted.moved.size(), 0.9 * static_cast<double>(V.rows())) << "seed " << seed;
    // The residual of 16 points about six coefficients: a little under σ.
    EXPECT_GT(fitted.noise, 0.5 * sigma) << "seed " << seed;
    EXPECT_LT(fitted.noise, 1.2 * sigma) << "seed " << seed;
    for (Eigen::Index v = 0; v < V.rows(); ++v) {
      if (!std::binary_search(fitted.moved.begin(), fitted.moved.end(), static_cast<int>(v))) {
        EXPECT_EQ(fitted.positions.row(v), V.row(v)) << "vertex " << v << " not moved, yet not where it was";
      }
    }
  }
}

// Noise as large as a stereo scan's against its spacing: some moves would
// carry a corner across its face's opposite edge, or fold a vertex's faces
// out of one hemisphere. Those faces keep their scanned corners.
TEST(JetFittedVertices, TurnNoFaceOver) {
  TriangleMesh mesh = sim::icosphere(4);
  const double spacing = mean_edge(mesh);
  sim::Random random(11);
  for (Eigen::Index v = 0; v < mesh.vertex_count(); ++v)
    for (int k = 0; k < 3; ++k) mesh.vertices.positions(v, k) += 0.3 * spacing * random.normal();
  const Eigen::MatrixX3d& V = mesh.vertices.positions;
  const JetFittedVertices fitted = jet_fitted_vertices(V, mesh.faces, 16);
  const auto normal = [&](const Eigen::MatrixX3d& P, Eigen::Index f) {
    const Eigen::RowVector3d a = P.row(mesh.faces(f, 0)), b = P.row(mesh.faces(f, 1)), c = P.row(mesh.faces(f, 2));
    return Eigen::RowVector3d((b - a).cross(c - a));
  };
  for (Eigen::Index f = 0; f < mesh.face_count(); ++f)
    EXPECT_GT(normal(fitted.positions, f).dot(normal(V, f)), 0.0) << "face " << f;
  // Nor does a vertex whose faces fit in a hemisphere lose that (the sign
  // condition of §9.6 needs it).
  std::vector<std::vector<Eigen::Index>> fan(static_cast<std::size_t>(V.rows()));
  for (Eigen::Index f = 0; f < mesh.face_count(); ++f)
    for (int k = 0; k < 3; ++k) fan[static_cast<std::size_t>(mesh.faces(f, k))].push_back(f);
  const auto hemispherical = [&](const Eigen::MatrixX3d& P, Eigen::Index v) {
    Eigen::RowVector3d sum = Eigen::RowVector3d::Zero();
    for (const Eigen::Index f : fan[static_cast<std::size_t>(v)]) sum += normal(P, f);
    return std::all_of(fan[static_cast<std::size_t>(v)].begin(), fan[static_cast<std::size_t>(v)].end(),
                       [&](Eigen::Index f) { return normal(P, f).dot(sum) > 0.0; });
  };
  for (Eigen::Index v = 0; v < V.rows(); ++v) {
    if (hemispherical(V, v)) {
      EXPECT_TRUE(hemispherical(fitted.positions, v)) << "vertex " << v;
    }
  }
  EXPECT_GT(fitted.moved.size(), 0.5 * static_cast<double>(V.rows()));
}

TEST(JetFittedVertices, KeepANoiseFreeSphereOnTheSphere) {
  // A quadric is no sphere: each jet misses its 16 points by a little, and
  // its vertex comes to lie off the sphere by as little (0.0013 of an edge
  // here), far below any scanner's noise.
  const TriangleMesh mesh = sim::icosphere(3);
  const JetFittedVertices fitted = jet_fitted_vertices(mesh.vertices.positions, mesh.faces, 16);
  const double edge = mean_edge(mesh);
  EXPECT_LT((fitted.positions.rowwise().norm().array() - 1.0).abs().maxCoeff(), 2e-3 * edge);
  EXPECT_LT((fitted.positions - mesh.vertices.positions).rowwise().norm().maxCoeff(), 3e-3 * edge);
  EXPECT_LT(fitted.noise, 1e-3 * edge);
}

TEST(JetFittedVertices, KeepTheRimsOfANoisyCan) {
  // A can of radius 1 and height 1 with flat ends: a quadric fitted across a
  // rim rounds it off; the rim's fit has a residual far above the noise, so
  // its vertices stay.
  std::vector<Eigen::Vector2d> profile;
  constexpr int steps = 20;
  for (int i = 0; i < steps; ++i) profile.emplace_back(double(i) / steps, 0.0);
  for (int i = 0; i < steps; ++i) profile.emplace_back(1.0, double(i) / steps);
  for (int i = steps; i >= 0; --i) profile.emplace_back(double(i) / steps, 1.0);
  Eigen::MatrixX2d P(static_cast<Eigen::Index>(profile.size()), 2);
  for (std::size_t i = 0; i < profile.size(); ++i) P.row(static_cast<Eigen::Index>(i)) = profile[i].transpose();
  TriangleMesh can = sim::surface_of_revolution(P, 120);
  constexpr double sigma = 0.001;
  sim::Random random(7);
  const Eigen::MatrixX3d truth = can.vertices.positions;
  for (Eigen::Index v = 0; v < can.vertex_count(); ++v)
    for (int k = 0; k < 3; ++k) can.vertices.positions(v, k) += sigma * random.normal();
  const Eigen::MatrixX3d& V = can.vertices.positions;
  const JetFittedVertices fitted = jet_fitted_vertices(V, can.faces, 16);
  int rims = 0, side = 0;
  double side_before = 0.0, side_after = 0.0;
  for (Eigen::Index v = 0; v < V.rows(); ++v) {
    const double r = truth.row(v).head<2>().norm(), z = truth(v, 2);
    if (std::abs(r - 1.0) < 1e-9 && (z < 1e-9 || z > 1.0 - 1e-9)) {
      ++rims;
      EXPECT_LT((fitted.positions.row(v) - V.row(v)).norm(), 3.0 * sigma) << "rim vertex " << v;
    } else if (std::abs(r - 1.0) < 1e-9 && z > 0.2 && z < 0.8) {
      ++side;
      side_before += std::pow(V.row(v).head<2>().norm() - 1.0, 2);
      side_after += std::pow(fitted.positions.row(v).head<2>().norm() - 1.0, 2);
    }
  }
  EXPECT_EQ(rims, 240);
  EXPECT_GT(side, 1000);
  EXPECT_LT(side_after, 0.6 * side_before);  // the wall itself is smoothed
}

TEST(JetFittedVertices, FitEachFaceOfAThinPlateOnItsOwn) {
  // A disc 2 wide and 0.02 thick: the nearest vertices of a point on one face
  // lie on the other face too; a jet through both would pull the faces
  // together.
  const TriangleMesh plate = sim::ellipsoid({1.0, 1.0, 0.01}, 3);
  const Eigen::MatrixX3d& V = plate.vertices.positions;
  const JetFittedVertices fitted = jet_fitted_vertices(V, plate.faces, 16);
  int checked = 0;
  for (Eigen::Index v = 0; v < V.rows(); ++v) {
    if (V.row(v).head<2>().norm() > 0.8) continue;  // the rim turns
    ++checked;
    EXPECT_LT(std::abs(fitted.positions(v, 2) - V(v, 2)), 1e-4) << "vertex " << v;
  }
  EXPECT_GT(checked, 100);
}

TEST(JetFittedVertices, NeedTenToAllTheVertices) {
  const TriangleMesh mesh = sim::icosphere(1);  // 42 vertices
  EXPECT_THROW(jet_fitted_vertices(mesh.vertices.positions, mesh.faces, 9), InvalidInput);
  EXPECT_THROW(jet_fitted_vertices(mesh.vertices.positions, mesh.faces, 43), InvalidInput);
  EXPECT_NO_THROW(jet_fitted_vertices(mesh.vertices.positions, mesh.faces, 42));
}

}  // namespace
}  // namespace scanstation
