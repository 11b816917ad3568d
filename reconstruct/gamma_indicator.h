// The γ-indicator: the selection key of constriction (thesis §5.2, §5.3).
#pragma once

#include <Eigen/Core>

namespace scanstation {

/// γ-indicator of the edge (a, b) with respect to the vertex l (Definition
/// 5.1): ±(1 − r/R) with r = |ab|/2 and R the circumradius of (a, b, l);
/// positive when the circumcentre lies on the same side of ab as l (Eq. 5.1).
/// Near −1: l almost on the edge (a wide angle at l); near +1: l far away.
double gamma_indicator(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& l);

/// γ-indicator of the triangle (a, b, c) with respect to the vertex l
/// (Definition 5.2): ±(1 − r/R), r the circumradius of (a, b, c), R that of
/// the tetrahedron (a, b, c, l); positive when the circumcentre lies on the
/// same side of the triangle's plane as l (Eq. 5.2). Returns 1 for a
/// tetrahedron too flat for its circumcentre to be computed.
double gamma_indicator(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                       const Eigen::Vector3d& l);

}  // namespace scanstation
