// Scattered points with optional per-point normals and colours.
#pragma once

#include <Eigen/Core>
#include <cstdint>

namespace scanstation {

using Point2 = Eigen::Vector2d;
using Point3 = Eigen::Vector3d;
using Colors = Eigen::Matrix<std::uint8_t, Eigen::Dynamic, 3>;

/// positions  #P by 3 coordinates; for planar data (dimension 2) z is 0
/// normals    #P by 3, or 0 by 3 when the source had none
/// colors     #P by 3 RGB in 0..255, or 0 by 3 when the source had none
/// dimension  2 for planar input (two coordinates per point), else 3
struct PointCloud {
  Eigen::MatrixX3d positions;
  Eigen::MatrixX3d normals;
  Colors colors;
  int dimension = 3;

  Eigen::Index size() const { return positions.rows(); }
  bool has_normals() const { return normals.rows() > 0; }
  bool has_colors() const { return colors.rows() > 0; }
};

}  // namespace scanstation
