#include "reconstruct/gamma_indicator.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace scanstation {

namespace {
// The construction only ranks candidates (no topology depends on it), so
// doubles suffice; the sign compares the sides of l and of the centre.
double signed_magnitude(double r_over_R, double side_vertex, double side_centre) {
  const double magnitude = std::clamp(1.0 - r_over_R, 0.0, 1.0);
  if (side_vertex * side_centre > 0) return magnitude;
  if (side_vertex * side_centre < 0) return -magnitude;
  return 0.0;
}
}  // namespace

double gamma_indicator(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& l) {
  // By the inscribed angle theorem |ab| = 2R sin θ, θ the angle at l, so
  // r/R = sin θ; and the circumcentre lies on l's side of ab exactly when θ
  // is acute. No circumcentre to construct: one division, no cancellation.
  const Eigen::Vector2d u = a - l, v = b - l;
  const double cross = u.x() * v.y() - u.y() * v.x(), dot = u.dot(v), lengths = u.norm() * v.norm();
  if (cross == 0.0 || !std::isfinite(lengths)) return 1.0;  // no circle through them
  return signed_magnitude(std::abs(cross) / lengths, dot, 1.0);  // Definition 5.1, Eq. (5.1)
}

double gamma_indicator(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                       const Eigen::Vector3d& l) {
  const Eigen::Vector3d u = a - l, v = b - l, w = c - l;  // circumcentre relative to l
  const double d = 2.0 * u.dot(v.cross(w));
  const Eigen::Vector3d centre =
      (u.squaredNorm() * v.cross(w) + v.squaredNorm() * w.cross(u) + w.squaredNorm() * u.cross(v)) / d;
  const double R2 = centre.squaredNorm();
  // Squared circumradius of the face: |e1|²|e2|²|e1−e2|² / (4|e1×e2|²);
  // r/R from the squares, one root instead of four.
  const Eigen::Vector3d e1 = b - a, e2 = c - a, n = e1.cross(e2);
  const double r2 = e1.squaredNorm() * e2.squaredNorm() * (e1 - e2).squaredNorm() / (4.0 * n.squaredNorm());
  if (!std::isfinite(R2) || !std::isfinite(r2) || R2 == 0.0) return 1.0;
  return signed_magnitude(std::sqrt(r2 / R2), n.dot(l - a), n.dot(centre + (l - a)));  // Definition 5.2, Eq. (5.2)
}

}  // namespace scanstation
