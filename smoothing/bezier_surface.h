// A piecewise cubic Bézier-triangle surface over a triangle mesh, as the
// splitting schemes of §9.6–§9.8 produce it.
#pragma once

#include "smoothing/bezier_triangle.h"

#include <vector>

namespace scanstation {

/// patches  the micro triangles; corners counter-clockwise from outside
/// macro    for each patch, the index of the input (macro) triangle it splits
/// dependent_edges  macro edges where the scheme's equations for the
///          cross-edge control points were dependent (e.g. Equation (9.4) on
///          an edge whose two ends look alike, as on a regular icosahedron):
///          the closest solution was taken and the edge need not be G¹
/// Adjacent patches share their common edge's four control points bit for bit.
struct BezierSurface {
  std::vector<CubicTriangle> patches;
  std::vector<int> macro;
  std::size_t dependent_edges = 0;
};

}  // namespace scanstation
