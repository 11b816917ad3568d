// The bounded damped least-squares step shared by the Step-5 solvers of the
// split schemes: where meeting the tangent-plane conditions exactly would
// move a control point too far (a bulge from nearly dependent conditions),
// the step that meets them as well as it can within a given reach.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <cmath>

namespace scanstation {

/// A (m by n) the linear conditions on n unknowns, r (m by 3) what they still
/// lack, D (k by n) the k points that the unknowns move (each a combination
/// of them). Returns the step x (n by 3) minimising |A x − r|² + μ|D x|² for
/// the smallest damping μ (found by bisection in log μ) that moves every one
/// of the k points at most `reach`: Levenberg–Marquardt's trust-region step,
/// measured on the points.
template <typename Conditions, typename Residual, typename Moved>
Eigen::Matrix<double, Conditions::ColsAtCompileTime, 3> damped_step(const Conditions& A, const Residual& r,
                                                                    double reach, const Moved& D) {
  constexpr int n = Conditions::ColsAtCompileTime;
  using Square = Eigen::Matrix<double, n, n>;
  using Points = Eigen::Matrix<double, n, 3>;
  const Square normal = A.transpose() * A;
  const Square metric = D.transpose() * D;
  const Points projected = A.transpose() * r;
  const double scale = normal.diagonal().maxCoeff() / metric.diagonal().maxCoeff();
  double lo = std::log(1e-12 * scale), hi = std::log(1e6 * scale);
  Points step = Points::Zero();
  for (int iteration = 0; iteration < 48; ++iteration) {
    const double mid = (lo + hi) / 2.0;
    const Points trial = (normal + std::exp(mid) * metric).ldlt().solve(projected);
    if ((D * trial).rowwise().norm().maxCoeff() <= reach) {
      step = trial;
      hi = mid;
    } else {
      lo = mid;
    }
  }
  return step;
}

/// The same with the unknowns themselves the points moved (D = I).
template <typename Conditions, typename Residual>
Eigen::Matrix<double, Conditions::ColsAtCompileTime, 3> damped_step(const Conditions& A, const Residual& r,
                                                                    double reach) {
  constexpr int n = Conditions::ColsAtCompileTime;
  return damped_step(A, r, reach, Eigen::Matrix<double, n, n>::Identity());
}

}  // namespace scanstation
