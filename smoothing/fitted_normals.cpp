#include "smoothing/fitted_normals.h"

#include "core/errors.h"
#include "smoothing/same_side_neighbours.h"

#include <Eigen/Eigenvalues>

#include <string>
#include <vector>

namespace scanstation {

namespace {

// cos 45°: the largest turn of a fitted normal from the face normals kept.
constexpr double kMostFromFaces = 0.70710678118654752;

}  // namespace

Eigen::MatrixX3d fitted_vertex_normals(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, int neighbours) {
  if (neighbours < 3 || neighbours > V.rows())
    throw InvalidInput("fitted normals: the neighbour count must be between 3 and the " + std::to_string(V.rows()) +
                       " vertices, got " + std::to_string(neighbours));
  const SameSideNeighbours around(V, F);
  return fitted_vertex_normals(V, around, neighbours);
}

Eigen::MatrixX3d fitted_vertex_normals(const Eigen::MatrixX3d& V, const SameSideNeighbours& around, int neighbours) {
  const Eigen::MatrixX3d& side = around.side();
  Eigen::MatrixX3d N = side;
  std::vector<Eigen::Index> near;
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    around.near(i, neighbours, near);
    if (near.size() < 3) continue;  // too few to fit a plane (none off the surface)
    Eigen::RowVector3d centre = Eigen::RowVector3d::Zero();
    for (const Eigen::Index j : near) centre += V.row(j);
    centre /= static_cast<double>(near.size());
    Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
    for (const Eigen::Index j : near) {
      const Eigen::Vector3d d = (V.row(j) - centre).transpose();
      scatter += d * d.transpose();
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> fit(scatter);
    // Neighbours on one line (or one point) hold no plane: the face normals stand.
    if (fit.info() != Eigen::Success || !(fit.eigenvalues()(1) > 1e-12 * fit.eigenvalues()(2))) continue;
    Eigen::Vector3d n = fit.eigenvectors().col(0);  // the smallest spread: the plane's normal
    if (n.dot(side.row(i).transpose()) < 0) n = -n;
    // A plane that turns more than 45° from the vertex's own faces does not
    // stand for them: a rim where a hull face closes space the scan never
    // saw (a bowl's lid over its unseen inside) or a sharp edge. The patches
    // over those faces would leave the vertex across them and fold out into
    // flaps (a scanned bowl's lid: 20 units off its triangles on an object
    // 92 across; 2.2 with this). The face normals stand there.
    if (n.dot(side.row(i).normalized().transpose()) < kMostFromFaces) continue;
    N.row(i) = n.transpose();
  }
  return N;
}

}  // namespace scanstation
