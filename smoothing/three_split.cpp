#include "smoothing/three_split.h"

#include "smoothing/damped_least_squares.h"
#include "smoothing/macro_patches.h"
#include "smoothing/tangent_plane_condition.h"

#include <Eigen/LU>
#include <cmath>

namespace scanstation {

namespace {

// Micro triangle k of a three-split: corners (V_k, V_k+1, C); in its control
// net b300..b030 is the macro edge, b201 = W_k, b111 = X_k, b021 = W_k+1,
// b102 = Y_k, b012 = Y_k+1, b003 = Z.
constexpr int W_first = control_index(2, 0, 1), X = control_index(1, 1, 1), W_second = control_index(0, 2, 1);
constexpr int Y_first = control_index(1, 0, 2), Y_second = control_index(0, 1, 2), Z = control_index(0, 0, 3);

// The ratio λ = e1/e0 of Equation (9.3) is free: (9.3a) and (9.3d) fix each
// end's coefficients only up to a factor. The thesis sets e0 = e1 = 1; with
// a least-squares ratio, λ > 0 minimises the displacement of L1 and R1 from
// their subdivided positions (x(λ) = c + λu + w/λ, a quartic in λ).
double closest_ratio(const Eigen::Matrix<double, 2, 3>& r, const Eigen::Matrix<double, 2, 3>& u,
                     const Eigen::Matrix<double, 2, 3>& w) {
  const auto cost = [&](double lambda) { return (r + lambda * u + w / lambda).squaredNorm(); };
  double best = 1.0;
  for (double log_lambda = -4.0; log_lambda <= 4.0; log_lambda += 0.125)
    if (cost(std::exp(log_lambda)) < cost(best)) best = std::exp(log_lambda);
  // Golden-section refinement in log λ around the best grid point.
  double lo = std::log(best) - 0.125, hi = std::log(best) + 0.125;
  constexpr double golden = 0.6180339887498949;
  for (int step = 0; step < 40; ++step) {
    const double a = hi - golden * (hi - lo), b = lo + golden * (hi - lo);
    (cost(std::exp(a)) < cost(std::exp(b)) ? hi : lo) = cost(std::exp(a)) < cost(std::exp(b)) ? b : a;
  }
  return std::exp((lo + hi) / 2.0);
}

}  // namespace

// Step 4: subdivision at the centroid.
void split_in_three(const CubicTriangle& macro, CubicTriangle* micro) {
  const Barycentric corner[3] = {Barycentric::UnitX(), Barycentric::UnitY(), Barycentric::UnitZ()};
  const Barycentric centre = Barycentric::Constant(1.0 / 3.0);
  for (int k = 0; k < 3; ++k) micro[k] = subpatch(macro, corner[k], corner[(k + 1) % 3], centre);
}

// Step 5 for one macro edge: the micro patch P on this side, Q on the other.
// M_i is P's edge row, L_i P's next row; R_i Q's next row read in P's direction.
bool join_three_split_edge(CubicTriangle& P, CubicTriangle& Q, bool least_squares_ratio, double max_move) {
  const Eigen::Vector3d M0 = P[control_index(3, 0, 0)], M1 = P[control_index(2, 1, 0)];
  const Eigen::Vector3d M2 = P[control_index(1, 2, 0)], M3 = P[control_index(0, 3, 0)];
  const Eigen::Vector3d L0 = P[W_first], L2 = P[W_second];
  const Eigen::Vector3d R0 = Q[W_second], R2 = Q[W_first];
  const Eigen::Vector2d c0 = end_coefficients(M1 - M0, L0 - M0, R0 - M0);  // Eq. (9.3a), e0 = 1
  const Eigen::Vector2d c1 = end_coefficients(M3 - M2, L2 - M2, R2 - M2);  // Eq. (9.3d), e1 = 1
  const bool ends_fit = end_fits(M1 - M0, L0 - M0, R0 - M0, c0) && end_fits(M3 - M2, L2 - M2, R2 - M2, c1);
  const double f0 = c0.x(), g0 = c0.y(), f1 = c1.x(), g1 = c1.y();
  // Equation (9.4) for x = (L1 − M1, R1 − M1), with (e1, f1, g1) scaled by λ:
  //   2f0 x_L + 2g0 x_R = −2(M2 − M1) − λ α
  //   2f1 x_L + 2g1 x_R = −2(M2 − M1) − β / λ
  const Eigen::Vector3d alpha = (M1 - M0) + f1 * (L0 - M0) + g1 * (R0 - M0);
  const Eigen::Vector3d beta = (M3 - M2) + f0 * (L2 - M2) + g0 * (R2 - M2);
  Eigen::Matrix2d A;
  A << 2 * f0, 2 * g0, 2 * f1, 2 * g1;
  Eigen::Matrix<double, 2, 3> fixed, with_lambda = Eigen::Matrix<double, 2, 3>::Zero(),
                                     with_inverse = Eigen::Matrix<double, 2, 3>::Zero(), old;
  fixed.row(0) = fixed.row(1) = -2.0 * (M2 - M1).transpose();
  with_lambda.row(0) = -alpha.transpose();
  with_inverse.row(1) = -beta.transpose();
  old.row(0) = (P[X] - M1).transpose();
  old.row(1) = (Q[X] - M1).transpose();
  // The unique solution when (9.4) is independent; when it is dependent
  // (rank 1), the closest one to the subdivided points (pseudo-inverse).
  const double scale = A.squaredNorm();
  const bool independent = std::abs(A.determinant()) > 1e-9 * scale;
  const Eigen::Matrix2d inverse = independent ? Eigen::Matrix2d(A.inverse()) : Eigen::Matrix2d(A.transpose() / scale);
  const auto solve = [&](const Eigen::Matrix<double, 2, 3>& rhs) -> Eigen::Matrix<double, 2, 3> {
    return inverse * (rhs - A * old);
  };
  // λ's sign: where (f0, g0) and (f1, g1) have opposite signs, λ > 0 lets F
  // and G both pass through zero along the edge and the surface fold between
  // them (see HalfEdge in six_split.cpp); λ < 0 keeps F/G > 0.
  const double sign = (f0 * f1 < 0.0 && g0 * g1 < 0.0) ? -1.0 : 1.0;
  const double lambda =
      sign * (least_squares_ratio && independent
                  ? closest_ratio(solve(fixed), sign * inverse * with_lambda, sign * inverse * with_inverse)
                  : 1.0);
  const Eigen::Matrix<double, 2, 3> rhs = fixed + lambda * with_lambda + with_inverse / lambda;
  Eigen::Matrix<double, 2, 3> solution = old + solve(rhs);
  // Nearly dependent conditions can demand L1, R1 far off the surface (a
  // bulge); within max_move edge lengths they are met as well as they can be.
  const double reach = max_move * (M3 - M0).norm();
  const bool bulges = (solution - old).rowwise().norm().maxCoeff() > reach;
  if (bulges) solution = old + damped_step(A, rhs - A * old, reach);
  P[X] = M1 + solution.row(0).transpose();
  Q[X] = M1 + solution.row(1).transpose();
  return independent && !bulges && ends_fit;
}

// Step 6 inside one macro triangle.
void join_three_split_interior(CubicTriangle* micro) {
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


BezierSurface three_split(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, const Eigen::MatrixX3d& N,
                          const MeshEdges& edges, const ThreeSplitOptions& options) {
  const std::vector<CubicTriangle> macro = macro_patches(V, F, N, options.tension);
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
      if (f < g && !join_three_split_edge(surface.patches[3 * f + e], surface.patches[3 * g + edges.neighbour_edge(f, e)],
                                          options.least_squares_ratio, options.max_move))
        surface.dependent_edges.push_back({f, g});
    }
  for (int f = 0; f < F.rows(); ++f) join_three_split_interior(&surface.patches[3 * f]);
  return surface;
}

}  // namespace scanstation
