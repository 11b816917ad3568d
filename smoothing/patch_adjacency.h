// Which patch edges of a Bézier surface meet, found from the control points
// alone (so checks do not trust the scheme that built the surface).
#pragma once

#include "smoothing/bezier_surface.h"

#include <vector>

namespace scanstation {

/// Edge k of a patch runs from corner k to corner k+1 (corners b300, b030,
/// b003). Two patch edges meet when their end corners are equal bit for bit
/// in opposite order.
struct PatchEdgePair {
  int patch_a, edge_a;
  int patch_b, edge_b;
};

/// pairs  every shared patch edge once
/// unmatched  patch edges with no partner (0 for a closed surface)
struct PatchAdjacency {
  std::vector<PatchEdgePair> pairs;
  std::size_t unmatched = 0;
};

PatchAdjacency patch_adjacency(const BezierSurface& surface);

/// Corner k (0..2) of a patch.
inline const Eigen::Vector3d& patch_corner(const CubicTriangle& patch, int k) {
  static constexpr int index[3] = {control_index(3, 0, 0), control_index(0, 3, 0), control_index(0, 0, 3)};
  return patch[index[k]];
}

/// The barycentric point at fraction s along edge k (from corner k to k+1).
inline Barycentric edge_parameter(int k, double s) {
  Barycentric p = Barycentric::Zero();
  p[k] = 1.0 - s;
  p[(k + 1) % 3] = s;
  return p;
}

}  // namespace scanstation
