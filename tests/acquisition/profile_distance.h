// Distance of a point to a surface of revolution given by its profile: the
// known answer of the simulated turntable scans.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <limits>

namespace scanstation::test {

/// Distance from (r, z) of `p` to the profile polyline (#P by 2, (r, z) rows).
inline double profile_distance(const Eigen::MatrixX2d& profile, const Eigen::Vector3d& p) {
  const Eigen::Vector2d q{p.head<2>().norm(), p.z()};
  double best = std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i + 1 < profile.rows(); ++i) {
    const Eigen::Vector2d a = profile.row(i), b = profile.row(i + 1);
    const double t = std::clamp((q - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
    best = std::min(best, (q - a - t * (b - a)).norm());
  }
  return best;
}

}  // namespace scanstation::test
