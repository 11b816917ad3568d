// Area and enclosed volume of triangle meshes.
#pragma once

#include <Eigen/Core>

namespace scanstation {

/// V #V by 3, F #F by 3. The sum of the triangle areas.
double surface_area(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F);

/// V #V by 3, F #F by 3 counter-clockwise from outside. The volume the
/// surface encloses (divergence theorem); meaningful for a closed, oriented
/// surface, negative when its faces point inwards.
double enclosed_volume(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F);

}  // namespace scanstation
