#include "core/bounding_box.h"

namespace scanstation {

namespace {
template <int D, typename Matrix>
Eigen::AlignedBox<double, D> box_of(const Matrix& P) {
  Eigen::AlignedBox<double, D> box;  // empty by default
  if (P.rows() > 0) {
    box.min() = P.colwise().minCoeff().transpose();
    box.max() = P.colwise().maxCoeff().transpose();
  }
  return box;
}
}  // namespace

Eigen::AlignedBox3d bounding_box(const Eigen::MatrixX3d& P) { return box_of<3>(P); }
Eigen::AlignedBox2d bounding_box(const Eigen::MatrixX2d& P) { return box_of<2>(P); }

}  // namespace scanstation
