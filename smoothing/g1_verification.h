// How continuous a Bézier surface really is: the tangent plane residual of
// Equation (8.7) and the angle between the unit normals of the two patches
// (Theorem 8.1) at sample points along every shared patch edge, and whether
// those normals point apart anywhere on it (exactly, not by samples).
#pragma once

#include "smoothing/bezier_surface.h"

#include <cstddef>

namespace scanstation {

/// max_normal_angle  radians; G¹ when at floating-point noise (≈1e-12)
/// max_residual  |[∇_d P, ∇_c P, ∇_c Q]| / (|∇_d P| |∇_c P| |∇_c Q|), the
///               scale-free Equation (8.7); 0 for tangent plane continuity
/// shared_edges, samples  what was measured; unmatched_edges  patch edges
///               without a partner (the surface is not closed)
struct G1Verification {
  double max_normal_angle = 0.0;
  /// the same over the patch edges neither on a macro edge of
  /// surface.dependent_edges nor inside its two macro triangles: where the
  /// scheme joined the patches exactly, at rounding level when the surface
  /// is G¹ there (not at vertices where the sign condition fails)
  double max_normal_angle_exact = 0.0;
  double max_residual = 0.0;
  std::size_t shared_edges = 0;
  std::size_t samples = 0;
  /// shared edges along which the two normals point apart somewhere (a
  /// fold, found exactly rather than by the samples; its angle counts as π)
  std::size_t folded_edges = 0;
  std::size_t unmatched_edges = 0;
};

/// samples_per_edge ≥ 1 interior points plus both ends of every shared edge.
G1Verification verify_g1(const BezierSurface& surface, int samples_per_edge = 7);

}  // namespace scanstation
