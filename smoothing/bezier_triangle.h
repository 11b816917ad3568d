// Cubic Bézier triangles (thesis §8.3.3): evaluation, directional derivatives
// (Equation 8.6), unit normals (Equation 8.4) and subpatches by blossoming.
#pragma once

#include <Eigen/Core>
#include <array>

namespace scanstation {

/// The ten control points b_ijk, i+j+k = 3, in the order
/// b300, b210, b201, b120, b111, b102, b030, b021, b012, b003, so that
/// P(u,v,w) = Σ b_ijk · 3!/(i!j!k!) · u^i v^j w^k with u+v+w = 1.
using CubicTriangle = std::array<Eigen::Vector3d, 10>;

/// Position of b_ijk in CubicTriangle (i+j+k = 3).
constexpr int control_index(int i, int /*j*/, int k) { return (3 - i) * (4 - i) / 2 + k; }

/// Barycentric parameter (u, v, w), u+v+w = 1.
using Barycentric = Eigen::Vector3d;

/// P(u, v, w).
Eigen::Vector3d evaluate(const CubicTriangle& patch, const Barycentric& uvw);

/// ∇_d P at uvw for a direction d with d1+d2+d3 = 0 (Equation 8.6).
Eigen::Vector3d directional_derivative(const CubicTriangle& patch, const Barycentric& uvw, const Eigen::Vector3d& d);

/// The unnormalised normal ∇_{(-1,1,0)}P × ∇_{(-1,0,1)}P: for corners ordered
/// counter-clockwise seen from outside it points outwards (Equation 8.4).
Eigen::Vector3d normal_direction(const CubicTriangle& patch, const Barycentric& uvw);

/// normal_direction normalised; where it vanishes (a singular point, e.g. a
/// corner whose two edge derivatives are parallel) the limit from the patch's
/// inside, taken a small step towards the centre; zero if that vanishes too.
Eigen::Vector3d unit_normal(const CubicTriangle& patch, const Barycentric& uvw);

/// The same surface restricted to the domain triangle whose corners have
/// barycentric coordinates r0, r1, r2 in the patch's domain: its control
/// points are the blossom values b_ijk = P[r0^i, r1^j, r2^k] (Bézier
/// subdivision, used in Step 4 of §9.6–§9.8).
CubicTriangle subpatch(const CubicTriangle& patch, const Barycentric& r0, const Barycentric& r1,
                       const Barycentric& r2);

/// One de Casteljau level of the blossom: the quadratic net P[a, ·, ·]
/// (order b200, b110, b101, b020, b011, b002), then the linear net
/// P[a, b, ·] (order b100, b010, b001). P[a, b, c] is the last level with c.
/// For splitting one patch into many sharing corners (the six-split).
using QuadraticNet = std::array<Eigen::Vector3d, 6>;
using LinearNet = std::array<Eigen::Vector3d, 3>;
QuadraticNet blossom_level(const CubicTriangle& patch, const Barycentric& a);
LinearNet blossom_level(const QuadraticNet& net, const Barycentric& b);
inline Eigen::Vector3d blossom_level(const LinearNet& net, const Barycentric& c) {
  return c[0] * net[0] + c[1] * net[1] + c[2] * net[2];
}

}  // namespace scanstation
