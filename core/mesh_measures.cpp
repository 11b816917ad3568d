#include "core/mesh_measures.h"

#include <Eigen/Geometry>

namespace scanstation {

namespace {
Eigen::Vector3d corner(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, Eigen::Index f, int k) {
  return V.row(F(f, k)).transpose();
}
}  // namespace

double surface_area(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F) {
  double area = 0.0;
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    area += 0.5 * (corner(V, F, f, 1) - corner(V, F, f, 0)).cross(corner(V, F, f, 2) - corner(V, F, f, 0)).norm();
  return area;
}

double enclosed_volume(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F) {
  double six = 0.0;
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    six += corner(V, F, f, 0).dot(corner(V, F, f, 1).cross(corner(V, F, f, 2)));
  return six / 6.0;
}

}  // namespace scanstation
