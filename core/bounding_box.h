// Axis-aligned bounding boxes of coordinate sets.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace scanstation {

/// P  #P by 3 (or by 2) coordinates; returns the smallest box holding them,
/// an empty box (isEmpty()) for #P = 0.
Eigen::AlignedBox3d bounding_box(const Eigen::MatrixX3d& P);
Eigen::AlignedBox2d bounding_box(const Eigen::MatrixX2d& P);

}  // namespace scanstation
