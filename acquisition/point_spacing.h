// Thinning of a scan's point stream to a least spacing: a point closer than
// the spacing to one kept before is dropped. Where a turntable scan's
// profiles crowd (near the top of an object, where the laser plane passes
// close to the axis, and wherever the spacing along a stripe is finer than
// between steps) the sensor noise is as large as the spacing: the boundary
// through every point is a fan of slivers there, its smooth surface creases,
// and each new step re-decides much of it (docs/design.md, "Least spacing").
// Greedy in arrival order, as the points stream in (Poisson-disk thinning,
// as MeshLab's and Open3D's samplers), so a live boundary fed step by step
// and a replay of the session keep the same points; thinning a thinned
// stream again changes nothing.
#pragma once

#include "acquisition/laser_triangulation.h"

#include <cstdint>
#include <unordered_map>
#include <vector>

namespace scanstation::acquisition {

class SpacingFilter {
 public:
  /// spacing  the least distance between two kept points (station units);
  ///          0 keeps every point. Throws InvalidInput when negative or
  ///          not finite.
  explicit SpacingFilter(double spacing);

  /// Drops from `points`, in order, every point within the spacing of a
  /// point kept before (by this filter, in this or an earlier call), with
  /// its colour and confidence. Returns how many were dropped. Throws
  /// InvalidInput for a point that is not finite or more than 2⁶²
  /// spacings from the origin.
  Eigen::Index thin(LaserScanPoints& points);

 private:
  bool near_kept(const Eigen::Vector3d& p, const Eigen::Vector3d& cell) const;

  double spacing_;
  std::unordered_map<std::uint64_t, std::vector<Eigen::Vector3d>> kept_;  // by cube of side `spacing`
};

}  // namespace scanstation::acquisition
