// The tangent plane continuity condition at one end of a common patch edge
// (thesis Equation 8.10 evaluated at an end point, e.g. Equations 9.3a, 9.9a).
#pragma once

#include <Eigen/Core>
#include <cmath>
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

/// Whether `c` (from end_coefficients) meets the condition: it cannot when
/// left ∥ right and `along` is off their line (as at a vertex of a cube whose
/// cross-edge points line up by symmetry): no tangent plane holds the end,
/// and the edge is not G¹ there whatever the scheme does inside it.
inline bool end_fits(const Eigen::Vector3d& along, const Eigen::Vector3d& left, const Eigen::Vector3d& right,
                     const Eigen::Vector2d& c) {
  const double scale = along.norm() + std::abs(c.x()) * left.norm() + std::abs(c.y()) * right.norm();
  return (along + c.x() * left + c.y() * right).norm() <= 1e-9 * scale;
}

}  // namespace scanstation
