// How far a smooth surface strays from the flat polyhedron it interpolates
// (the wild oscillation of the three-split, thesis Figure 9.5 vs 9.8).
#pragma once

#include "smoothing/bezier_surface.h"

#include <Eigen/Core>

namespace scanstation {

/// max_relative  max over samples of dist(sample, its macro triangle) divided
///               by that triangle's mean edge length
/// mean_relative the same, averaged over all samples
/// max_distance  max over samples of dist(sample, its macro triangle), in the
///               mesh's units (a bulge on a long edge is small relative to it
///               but large against the object)
struct Oscillation {
  double max_relative = 0.0;
  double mean_relative = 0.0;
  double max_distance = 0.0;
};

/// surface from a splitting scheme over V (#V by 3), F (#F by 3);
/// samples_per_edge  grid density per patch (≥ 1).
Oscillation oscillation(const BezierSurface& surface, const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F,
                        int samples_per_edge = 6);

}  // namespace scanstation
