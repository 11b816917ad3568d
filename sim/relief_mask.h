// A relief "mask": a closed solid whose front is a face-like height field,
// standing in for the laser-range mask of the thesis (Figures 1.1, 5.6).
#pragma once

#include "core/triangle_mesh.h"

#include <Eigen/Core>

namespace scanstation::sim {

/// The front height of the mask above the plane z = 0 at (x, y) inside the
/// ellipse (x/0.7)² + y² ≤ 1: a dome with a nose, brow ridge, eye sockets,
/// lips and chin, tapering to 0 at the rim. Outside the ellipse: 0.
double relief_mask_height(double x, double y);

/// The closed mask: the front height field over a polar grid of `rings`
/// rings and `segments` segments, joined at the rim to a shallow back dome.
/// Returns a closed, outward-oriented genus-0 mesh with
/// 2 + (2·rings − 1)·segments vertices. Throws InvalidInput for rings < 2 or
/// segments < 3.
TriangleMesh relief_mask(int rings, int segments);

}  // namespace scanstation::sim
