// The exact power-of-two scale that brings coordinates to magnitudes near 1.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

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

/// Whether coordinates whose unit_scale is `scale` can give measures whose
/// intermediate terms leave the double range: beyond 2^±100 (the scale's
/// exponent), as the squared length of a cross product of edges, the fourth
/// power of the coordinates' scale, can, even for the shortest edges
/// rounding allows. Then measures are taken on the scaled copy and scaled
/// back (exact); within it they are taken as they are, the same to the bit.
inline bool beyond_squares(double scale) { return std::abs(std::ilogb(scale)) > 100; }

/// The Euclidean norm of v without overflow or underflow of its squares:
/// v's norm to the bit wherever that is representable.
template <typename Derived>
double scaled_norm(const Eigen::MatrixBase<Derived>& v) {
  // Plain vectors, so that the sum of squares runs in the order Eigen sums
  // a plain vector's (an expression of ldexp would add them the other way
  // round, a last bit apart).
  const typename Derived::PlainObject plain = v;
  const double largest = plain.size() > 0 ? plain.cwiseAbs().maxCoeff() : 0.0;
  if (!(largest > 0.0) || !std::isfinite(largest)) return plain.norm();
  int exponent = 0;
  std::frexp(largest, &exponent);
  const typename Derived::PlainObject scaled = plain.unaryExpr([exponent](double x) { return std::ldexp(x, -exponent); });
  return std::ldexp(scaled.norm(), exponent);
}

/// v times the power of two that brings its largest |component| into
/// [1/2, 1): the same direction, exactly (v itself when zero or not finite).
template <int N>
Eigen::Matrix<double, N, 1> near_unit(const Eigen::Matrix<double, N, 1>& v) {
  const double largest = v.cwiseAbs().maxCoeff();
  if (!(largest > 0.0) || !std::isfinite(largest)) return v;
  int exponent = 0;
  std::frexp(largest, &exponent);
  return v.unaryExpr([exponent](double x) { return std::ldexp(x, -exponent); });
}

/// A vector along u × v whose length is near 1 at any scale of u and v: the
/// factors and the product brought near unit length by powers of two, so
/// that neither it nor its squared length overflows (coordinates near 1e160)
/// or underflows (near 1e-160) where u × v itself would. Zero when u and v
/// are parallel. The scalings are exact: normalized, it is bit for bit the
/// normalized u × v wherever that one is representable.
inline Eigen::Vector3d scaled_cross(const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
  return near_unit(near_unit(u).cross(near_unit(v)));
}

}  // namespace scanstation
