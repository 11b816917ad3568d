#include "smoothing/macro_patches.h"

namespace scanstation {

CubicTriangle macro_patch(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, const Eigen::MatrixX3d& N,
                          Eigen::Index f, double tension) {
  CubicTriangle b;
  const Eigen::Vector3d p0 = V.row(F(f, 0)), p1 = V.row(F(f, 1)), p2 = V.row(F(f, 2));
  const Eigen::Vector3d n0 = N.row(F(f, 0)), n1 = N.row(F(f, 1)), n2 = N.row(F(f, 2));
  b[control_index(3, 0, 0)] = p0;  // Step 1
  b[control_index(0, 3, 0)] = p1;
  b[control_index(0, 0, 3)] = p2;
  b[control_index(2, 1, 0)] = edge_control_point(p0, n0, p1, tension);  // Step 2
  b[control_index(2, 0, 1)] = edge_control_point(p0, n0, p2, tension);
  b[control_index(1, 2, 0)] = edge_control_point(p1, n1, p0, tension);
  b[control_index(0, 2, 1)] = edge_control_point(p1, n1, p2, tension);
  b[control_index(1, 0, 2)] = edge_control_point(p2, n2, p0, tension);
  b[control_index(0, 1, 2)] = edge_control_point(p2, n2, p1, tension);
  set_centre_point(b);
  return b;
}

void set_centre_point(CubicTriangle& b) {
  const Eigen::Vector3d edge_sum = b[control_index(2, 1, 0)] + b[control_index(1, 2, 0)] +
                                   b[control_index(2, 0, 1)] + b[control_index(1, 0, 2)] +
                                   b[control_index(0, 2, 1)] + b[control_index(0, 1, 2)];
  const Eigen::Vector3d corner_sum = b[control_index(3, 0, 0)] + b[control_index(0, 3, 0)] + b[control_index(0, 0, 3)];
  b[control_index(1, 1, 1)] = edge_sum / 4.0 - corner_sum / 6.0;  // Step 3
}

std::vector<CubicTriangle> macro_patches(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F,
                                         const Eigen::MatrixX3d& N, double tension) {
  std::vector<CubicTriangle> patches(F.rows());
  for (Eigen::Index f = 0; f < F.rows(); ++f) patches[f] = macro_patch(V, F, N, f, tension);
  return patches;
}

}  // namespace scanstation
