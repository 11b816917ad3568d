// Steps 1–3 of the splitting schemes (thesis §9.6): one cubic Bézier triangle
// per input triangle, interpolating its vertices and their normals.
#pragma once

#include "smoothing/bezier_triangle.h"

#include <Eigen/Core>
#include <vector>

namespace scanstation {

/// V #V by 3, F #F by 3, N #V by 3 unit normals.
/// Step 1: b300, b030, b003 are the triangle's corners. Step 2: b210 =
/// b300 + t(b030* − b300) with b030* the projection of b030 onto the tangent
/// plane at b300, and symmetrically; t = `tension`, 1/3 in the thesis, which
/// notes (§9.9) that this constant acts as a tension parameter at the
/// vertices. Step 3 [Farin, 83]: b111 = (sum of the six edge points)/4 −
/// (sum of the corners)/6.
/// returns  #F patches, patch f with corners V(F(f,0)), V(F(f,1)), V(F(f,2)).
std::vector<CubicTriangle> macro_patches(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F,
                                         const Eigen::MatrixX3d& N, double tension = 1.0 / 3.0);

/// The patch of triangle f alone (macro_patches()[f]), for schemes that split
/// it at once instead of keeping all macro patches.
CubicTriangle macro_patch(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, const Eigen::MatrixX3d& N,
                          Eigen::Index f, double tension);

/// Step 3 alone: b111 from the corners and the six edge points (for schemes
/// that move edge points after Step 2).
void set_centre_point(CubicTriangle& patch);

/// The Step-2 point of the edge from a (unit normal n) towards b:
/// a + t(b* − a), b* the projection of b onto the tangent plane at a.
inline Eigen::Vector3d edge_control_point(const Eigen::Vector3d& a, const Eigen::Vector3d& n,
                                          const Eigen::Vector3d& b, double tension) {
  const Eigen::Vector3d d = b - a;
  return a + (d - n * n.dot(d)) * tension;
}

}  // namespace scanstation
