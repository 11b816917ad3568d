#include "smoothing/g1_verification.h"

#include "smoothing/patch_adjacency.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace scanstation {

namespace {

Eigen::Vector3d unit_vector(int k) { return Barycentric::Unit(k); }

}  // namespace

G1Verification verify_g1(const BezierSurface& surface, int samples_per_edge) {
  const PatchAdjacency adjacency = patch_adjacency(surface);
  G1Verification result;
  result.shared_edges = adjacency.pairs.size();
  result.unmatched_edges = adjacency.unmatched;
  const int n = samples_per_edge + 1;
  for (const PatchEdgePair& pair : adjacency.pairs) {
    const CubicTriangle& P = surface.patches[pair.patch_a];
    const CubicTriangle& Q = surface.patches[pair.patch_b];
    const int a = pair.edge_a, b = pair.edge_b;
    const Eigen::Vector3d along = unit_vector((a + 1) % 3) - unit_vector(a);   // d
    const Eigen::Vector3d across_p = unit_vector((a + 2) % 3) - unit_vector(a);  // c in P
    const Eigen::Vector3d across_q = unit_vector((b + 2) % 3) - unit_vector(b);  // c in Q
    for (int i = 0; i <= n; ++i) {
      const double s = double(i) / n;
      const Barycentric at_p = edge_parameter(a, s), at_q = edge_parameter(b, 1.0 - s);
      const Eigen::Vector3d dP = directional_derivative(P, at_p, along);
      const Eigen::Vector3d cP = directional_derivative(P, at_p, across_p);
      const Eigen::Vector3d cQ = directional_derivative(Q, at_q, across_q);
      const double scale = dP.norm() * cP.norm() * cQ.norm();
      if (scale > 0.0) result.max_residual = std::max(result.max_residual, std::abs(dP.cross(cP).dot(cQ)) / scale);
      const Eigen::Vector3d nP = normal_direction(P, at_p), nQ = normal_direction(Q, at_q);
      // A vanishing normal is a singular point: no tangent plane, not G¹.
      const bool singular = nP.squaredNorm() == 0.0 || nQ.squaredNorm() == 0.0;
      const double angle = singular ? M_PI : std::atan2(nP.cross(nQ).norm(), nP.dot(nQ));
      result.max_normal_angle = std::max(result.max_normal_angle, angle);
      ++result.samples;
    }
  }
  return result;
}

}  // namespace scanstation
