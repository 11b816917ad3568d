// The tangent plane continuity condition at one end of a common patch edge
// (thesis Equation 8.10 evaluated at an end point, e.g. Equations 9.3a, 9.9a).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace scanstation {

/// Coefficients (f, g) with along + f·left + g·right = 0, i.e. e = 1 in
/// e(M1 − M0) + f(L0 − M0) + g(R0 − M0) = 0. The three vectors lie in one
/// tangent plane; the 2×2 normal equations of the least-squares fit absorb
/// rounding. (f, g) both negative means L0 and R0 lie on opposite sides of
/// the edge direction: the G¹ sign condition.
inline Eigen::Vector2d end_coefficients(const Eigen::Vector3d& along, const Eigen::Vector3d& left,
                                        const Eigen::Vector3d& right) {
  const double ll = left.dot(left), lr = left.dot(right), rr = right.dot(right);
  const double la = left.dot(along), ra = right.dot(along);
  const double det = ll * rr - lr * lr;
  if (det > 1e-24 * ll * rr) return {(-la * rr + ra * lr) / det, (-ra * ll + la * lr) / det};
  // Degenerate ends (left ∥ right, or a zero vector, where the vertex normal
  // is nearly perpendicular to its faces): the smallest (f, g) that fits,
  // finite, so the rest of the surface is still built; the edge is then not G¹
  // and the verification reports it.
  const double scale = ll + rr;
  return scale > 0.0 ? Eigen::Vector2d(-la / scale, -ra / scale) : Eigen::Vector2d::Zero();
}

}  // namespace scanstation
