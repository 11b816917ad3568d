#include "acquisition/point_spacing.h"

#include "acquisition/outlier_removal.h"
#include "core/errors.h"

#include <cmath>
#include <string>

namespace scanstation::acquisition {

namespace {

// The cube of side `side` holding p, as whole numbers; a point too far for
// 64-bit cube numbers (or not finite) is refused.
Eigen::Vector3d cube_of(const Eigen::Vector3d& p, double side) {
  const Eigen::Vector3d cell = (p / side).array().floor();
  constexpr double limit = 0x1p62;
  if (!((cell.array().abs() < limit).all()))
    throw InvalidInput("least point spacing: the point (" + std::to_string(p.x()) + ", " + std::to_string(p.y()) +
                       ", " + std::to_string(p.z()) + ") is not finite or more than 2^62 spacings of " +
                       std::to_string(side) + " from the origin");
  return cell;
}

// A hash of a cube's numbers. Cubes may share one: their points are then
// checked too, by distance, which only costs time.
std::uint64_t cube_key(const Eigen::Vector3d& cell) {
  const auto u = [](double v) { return static_cast<std::uint64_t>(static_cast<std::int64_t>(v)); };
  return u(cell.x()) * 0x9E3779B97F4A7C15ULL ^ u(cell.y()) * 0xC2B2AE3D27D4EB4FULL ^ u(cell.z()) * 0x165667B19E3779F9ULL;
}

}  // namespace

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
    const Eigen::Vector3d cell = cube_of(p, spacing_);
    if (near_kept(p, cell)) continue;
    kept_[cube_key(cell)].push_back(p);
    kept.push_back(i);
  }
  return keep_points(points, kept);
}

}  // namespace scanstation::acquisition
