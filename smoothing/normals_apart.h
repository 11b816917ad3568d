// Whether two normal fields along one edge point apart anywhere on it,
// decided exactly rather than by samples: both are cross products of
// quadratic derivatives, so their dot product is a polynomial of degree 8,
// whose Bernstein coefficients bound it (thesis §8.2: a fold is a normal
// turned by π where the tangent planes agree).
#pragma once

#include <Eigen/Core>

#include <array>

namespace scanstation {

/// A quartic vector polynomial on [0, 1] by its Bernstein coefficients.
using Quartic = std::array<Eigen::Vector3d, 5>;

/// The quadratic with Bernstein coefficients b[0..2] at s.
inline Eigen::Vector3d quadratic(const Eigen::Vector3d* b, double s) {
  const double t = 1.0 - s;
  return (t * t) * b[0] + (2.0 * s * t) * b[1] + (s * s) * b[2];
}

/// a(s) × b(s) for two quadratics given by their Bernstein coefficients.
Quartic cross_product(const Eigen::Vector3d* a, const Eigen::Vector3d* b);

/// Whether p(s)·q(s) ≤ 0 somewhere on [0, 1]: no when all of its Bernstein
/// coefficients are positive, yes when an end value is ≤ 0; otherwise the
/// interval is halved (de Casteljau) down to 2^-16, beyond which a positive
/// coefficient-undecided stretch counts as no (a normal that only touches
/// zero is left to rounding).
bool reaches_zero(const Quartic& p, const Quartic& q);

/// q(1 − s): the same quartic run the other way.
inline Quartic reversed(const Quartic& q) { return {q[4], q[3], q[2], q[1], q[0]}; }

}  // namespace scanstation
