// Smallest enclosing disc/ball of a point set (CGAL Min_sphere_of_spheres_d,
// expected linear time), with the input vertices it touches.
#pragma once

#include <Eigen/Core>

#include <vector>

namespace scanstation {

/// P  #P by D positions (D = 2 or 3), #P ≥ 1.
template <int D>
struct EnclosingBall {
  Eigen::Matrix<double, D, 1> center;
  double radius = 0.0;
  std::vector<int> support;  ///< rows of P on the boundary that determine the ball
};

template <int D>
EnclosingBall<D> smallest_enclosing_ball(const Eigen::Matrix<double, Eigen::Dynamic, D>& P);

}  // namespace scanstation
