// The exact power-of-two scale that brings coordinates to magnitudes near 1.
#pragma once

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <limits>

namespace scanstation {

/// The power of two s that brings the largest |coordinate| of P into
/// [1/2, 1), so that squared lengths, circumcentres and lens balls built
/// from P·s neither overflow nor underflow. Multiplying by s is exact, so
/// every exact predicate answers on P·s as on P, and any result built from
/// predicates and ratios (a triangulation, a γ-graph, a constriction) is
/// the same. Subnormal input scales by 2^1023 at most, the largest power of
/// two a double holds.
/// P  finite coordinates (any shape)
/// Returns 1 for an empty or all-zero P, and when scaling down would push a
/// nonzero coordinate below the normal range (within 53 bits of it), where
/// it would lose bits and distinct points could merge.
template <typename Derived>
double unit_scale(const Eigen::MatrixBase<Derived>& P) {
  const double largest = P.size() > 0 ? P.cwiseAbs().maxCoeff() : 0.0;
  if (!(largest > 0.0)) return 1.0;
  int exponent = 0;
  std::frexp(largest, &exponent);
  const double scale = std::ldexp(1.0, std::min(-exponent, std::numeric_limits<double>::max_exponent - 1));
  if (scale >= 1.0) return scale;
  double smallest = std::numeric_limits<double>::infinity();
  for (Eigen::Index j = 0; j < P.cols(); ++j)
    for (Eigen::Index i = 0; i < P.rows(); ++i)
      if (P(i, j) != 0.0) smallest = std::min(smallest, std::abs(P(i, j)));
  return smallest * scale < std::numeric_limits<double>::min() * 0x1p53 ? 1.0 : scale;
}

}  // namespace scanstation
