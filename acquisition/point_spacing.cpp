#include "acquisition/point_spacing.h"

#include "acquisition/outlier_removal.h"
#include "acquisition/point_grid.h"
#include "core/errors.h"

#include <cmath>
#include <string>

namespace scanstation::acquisition {

SpacingFilter::SpacingFilter(double spacing) : spacing_(spacing) {
  if (!(std::isfinite(spacing) && spacing >= 0))
    throw InvalidInput("least point spacing: expected a number ≥ 0 (0 = keep every point), got " +
                       std::to_string(spacing));
}

bool SpacingFilter::near_kept(const Eigen::Vector3d& p, const Eigen::Vector3d& cell) const {
  const double squared = spacing_ * spacing_;
  for (int dx = -1; dx <= 1; ++dx)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dz = -1; dz <= 1; ++dz) {
        const auto it = kept_.find(cube_key(cell + Eigen::Vector3d(dx, dy, dz)));
        if (it == kept_.end()) continue;
        for (const Eigen::Vector3d& q : it->second)
          if ((q - p).squaredNorm() < squared) return true;
      }
  return false;
}

Eigen::Index SpacingFilter::thin(LaserScanPoints& points) {
  if (spacing_ == 0) return 0;
  std::vector<Eigen::Index> kept;
  const Eigen::MatrixX3d& P = points.cloud.positions;
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    const Eigen::Vector3d p = P.row(i).transpose();
    const Eigen::Vector3d cell = cube_of(p, spacing_, "least point spacing");
    if (near_kept(p, cell)) continue;
    kept_[cube_key(cell)].push_back(p);
    kept.push_back(i);
  }
  return keep_points(points, kept);
}

}  // namespace scanstation::acquisition
