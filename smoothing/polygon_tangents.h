// Unit tangent vectors at the vertices of a closed polygon (thesis §9.2).
#pragma once

#include "core/polygon.h"

#include <Eigen/Core>

namespace scanstation {

/// How the two edges at a vertex are weighted (§9.2, methods 1–3).
enum class TangentWeighting {
  length,          ///< method 1: v(i+1) − v(i−1); longer edges count more (the thesis' choice)
  uniform,         ///< method 2: sum of the two unit edge vectors
  inverse_length,  ///< method 3: edges divided by their squared length; near neighbours count more
};

/// polygon  #N ≥ 3 vertices, closed implicitly, no two consecutive equal
/// weighting  one of the three estimates of §9.2
/// returns  #N by 2 unit tangents T_i, oriented along the polygon's order.
/// Throws InvalidInput on repeated consecutive vertices (naming the vertex) or
/// when a weighted sum vanishes (an exact reversal, v(i+1) = v(i−1)).
Eigen::MatrixX2d polygon_tangents(const Polygon2& polygon, TangentWeighting weighting = TangentWeighting::length);

}  // namespace scanstation
