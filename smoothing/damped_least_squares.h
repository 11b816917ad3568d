// The bounded damped least-squares step shared by the Step-5 solvers of the
// split schemes: where meeting the tangent-plane conditions exactly would
// move a control point too far (a bulge from nearly dependent conditions),
// the step that meets them as well as it can within a given reach.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <cmath>

namespace scanstation {

/// A (m by n) the linear conditions on n unknown points, r (m by 3) what they
/// still lack. Returns the step x (n by 3) minimising |A x − r|² + μ|x|² for
/// the smallest damping μ (found by bisection in log μ) whose every row is at
/// most `reach` long: Levenberg–Marquardt's trust-region step.
template <typename Conditions, typename Residual>
Eigen::Matrix<double, Conditions::ColsAtCompileTime, 3> damped_step(const Conditions& A, const Residual& r,
                                                                    double reach) {
  constexpr int n = Conditions::ColsAtCompileTime;
  using Square = Eigen::Matrix<double, n, n>;
  using Points = Eigen::Matrix<double, n, 3>;
  const Square normal = A.transpose() * A;
  const Points projected = A.transpose() * r;
  const double scale = normal.diagonal().maxCoeff();
  double lo = std::log(1e-12 * scale), hi = std::log(1e6 * scale);
  Points step = Points::Zero();
  for (int iteration = 0; iteration < 48; ++iteration) {
    const double mid = (lo + hi) / 2.0;
    const Points trial = (normal + std::exp(mid) * Square::Identity()).ldlt().solve(projected);
    if (trial.rowwise().norm().maxCoeff() <= reach) {
      step = trial;
      hi = mid;
    } else {
      lo = mid;
    }
  }
  return step;
}

}  // namespace scanstation
