#include "smoothing/three_split.h"

#include "smoothing/macro_patches.h"
#include "smoothing/tangent_plane_condition.h"

#include <Eigen/LU>
#include <Eigen/SVD>

namespace scanstation {

namespace {

// Micro triangle k of a three-split: corners (V_k, V_k+1, C); in its control
// net b300..b030 is the macro edge, b201 = W_k, b111 = X_k, b021 = W_k+1,
// b102 = Y_k, b012 = Y_k+1, b003 = Z.
constexpr int W_first = control_index(2, 0, 1), X = control_index(1, 1, 1), W_second = control_index(0, 2, 1);
constexpr int Y_first = control_index(1, 0, 2), Y_second = control_index(0, 1, 2), Z = control_index(0, 0, 3);

// Step 4: subdivision at the centroid.
void split_in_three(const CubicTriangle& macro, CubicTriangle* micro) {
  const Barycentric corner[3] = {Barycentric::UnitX(), Barycentric::UnitY(), Barycentric::UnitZ()};
  const Barycentric centre = Barycentric::Constant(1.0 / 3.0);
  for (int k = 0; k < 3; ++k) micro[k] = subpatch(macro, corner[k], corner[(k + 1) % 3], centre);
}

// Step 5 for one macro edge: the micro patch P on this side, Q on the other.
// M_i is P's edge row, L_i P's next row; R_i Q's next row read in P's direction.
bool join_macro_edge(CubicTriangle& P, CubicTriangle& Q) {
  const Eigen::Vector3d M0 = P[control_index(3, 0, 0)], M1 = P[control_index(2, 1, 0)];
  const Eigen::Vector3d M2 = P[control_index(1, 2, 0)], M3 = P[control_index(0, 3, 0)];
  const Eigen::Vector3d L0 = P[W_first], L2 = P[W_second];
  const Eigen::Vector3d R0 = Q[W_second], R2 = Q[W_first];
  const Eigen::Vector2d c0 = end_coefficients(M1 - M0, L0 - M0, R0 - M0);  // Eq. (9.3a), e0 = 1
  const Eigen::Vector2d c1 = end_coefficients(M3 - M2, L2 - M2, R2 - M2);  // Eq. (9.3d), e1 = 1
  const double f0 = c0.x(), g0 = c0.y(), f1 = c1.x(), g1 = c1.y();
  // Equation (9.4): two vector equations in L1, R1.
  const Eigen::Vector3d rhs0 = 2 * f0 * M1 + 2 * g0 * M1 - (M1 - M0) - 2 * (M2 - M1) - f1 * (L0 - M0) - g1 * (R0 - M0);
  const Eigen::Vector3d rhs1 = 2 * f1 * M1 + 2 * g1 * M1 - 2 * (M2 - M1) - (M3 - M2) - f0 * (L2 - M2) - g0 * (R2 - M2);
  Eigen::Matrix2d A;
  A << 2 * f0, 2 * g0, 2 * f1, 2 * g1;
  Eigen::Matrix<double, 2, 3> rhs;
  rhs.row(0) = rhs0.transpose();
  rhs.row(1) = rhs1.transpose();
  Eigen::Matrix<double, 2, 3> old;
  old.row(0) = P[X].transpose();
  old.row(1) = Q[X].transpose();
  // Closest solution to the subdivided points; the unique one when (9.4) is
  // independent.
  Eigen::JacobiSVD<Eigen::Matrix2d> svd(A, Eigen::ComputeFullU | Eigen::ComputeFullV);
  svd.setThreshold(1e-9);
  const Eigen::Matrix<double, 2, 3> solution = old + svd.solve(rhs - A * old);
  P[X] = solution.row(0).transpose();
  Q[X] = solution.row(1).transpose();
  return svd.rank() == 2;
}

// Step 6 inside one macro triangle.
void join_micro_edges(CubicTriangle* micro) {
  for (int k = 0; k < 3; ++k) {
    CubicTriangle& after = micro[k];
    CubicTriangle& before = micro[(k + 2) % 3];
    const Eigen::Vector3d Y = (after[W_first] + after[X] + before[X]) / 3.0;
    after[Y_first] = Y;
    before[Y_second] = Y;
  }
  const Eigen::Vector3d centre = (micro[0][Y_first] + micro[1][Y_first] + micro[2][Y_first]) / 3.0;
  for (int k = 0; k < 3; ++k) micro[k][Z] = centre;
}

}  // namespace

BezierSurface three_split(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, const Eigen::MatrixX3d& N,
                          const MeshEdges& edges) {
  const std::vector<CubicTriangle> macro = macro_patches(V, F, N);
  BezierSurface surface;
  surface.patches.resize(3 * F.rows());
  surface.macro.resize(3 * F.rows());
  for (int f = 0; f < F.rows(); ++f) {
    split_in_three(macro[f], &surface.patches[3 * f]);
    for (int k = 0; k < 3; ++k) surface.macro[3 * f + k] = f;
  }
  for (int f = 0; f < F.rows(); ++f)
    for (int e = 0; e < 3; ++e) {
      const int g = edges.neighbour(f, e);
      if (f < g && !join_macro_edge(surface.patches[3 * f + e], surface.patches[3 * g + edges.neighbour_edge(f, e)]))
        ++surface.dependent_edges;
    }
  for (int f = 0; f < F.rows(); ++f) join_micro_edges(&surface.patches[3 * f]);
  return surface;
}

}  // namespace scanstation
