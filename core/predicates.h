// Exact geometric predicates over plain Eigen points.
//
// Every topological decision in scanstation (which side, inside which circle
// or sphere) goes through these, never through a floating-point guess. They
// are CGAL's filtered exact predicates (Exact_predicates_inexact_constructions
// kernel): exact for any double input, fast when the answer is clear.
#pragma once

#include <Eigen/Core>

namespace scanstation {

/// Sign of the orientation of (a, b, c): +1 counter-clockwise (left turn),
/// -1 clockwise, 0 collinear.
int orientation(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c);

/// Sign of the orientation of (a, b, c, d): +1 when d lies on the positive
/// side of the plane through a, b, c (CGAL's POSITIVE: (a,b,c,d) is a
/// positively oriented tetrahedron), -1 on the other side, 0 coplanar.
int orientation(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                const Eigen::Vector3d& d);

/// For a counter-clockwise triangle (a, b, c): +1 when d is strictly inside its
/// circumcircle, -1 outside, 0 on it. Sign flips for a clockwise triangle.
int side_of_oriented_circle(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                            const Eigen::Vector2d& d);

/// For a positively oriented tetrahedron (a, b, c, d): +1 when e is strictly
/// inside its circumsphere, -1 outside, 0 on it.
int side_of_oriented_sphere(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                            const Eigen::Vector3d& d, const Eigen::Vector3d& e);

/// Whether a, b, c lie on one line (two or three of them equal included),
/// decided exactly.
bool collinear(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c);

/// Whether every row of V lies on one line (fewer than three distinct
/// points included), decided exactly, in one pass. CGAL's 2D triangulation
/// of collinear points locates each insertion by a walk along the line:
/// quadratic time (20k points took seconds), so callers ask this first.
bool all_collinear(const Eigen::MatrixX2d& V);

/// Whether every row of V lies in one plane (fewer than four points, or all
/// on one line, included), decided exactly.
bool all_coplanar(const Eigen::MatrixX3d& V);

}  // namespace scanstation
