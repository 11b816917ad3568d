#include "smoothing/g1_verification.h"

#include "smoothing/patch_adjacency.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace scanstation {

namespace {

// Along patch edge k (corner k → k+1) the derivatives that Equation (8.7)
// and the normal need are quadratics: along the edge, with the Bernstein
// coefficients M_i+1 − M_i of its row M_0..M_3, and across it towards corner
// k+2, with L_i − M_i (L the next row). Their cross product is the normal of
// Equation (8.4) up to a positive factor (any two directions in the same
// turning sense span the same oriented tangent plane).
struct EdgeDerivatives {
  Eigen::Vector3d along[3], across[3];
  EdgeDerivatives(const CubicTriangle& patch, int k) {
    int M[4], L[3];
    for (int i = 0; i <= 3; ++i) {
      int exponent[3] = {0, 0, 0};
      exponent[k] = 3 - i;
      exponent[(k + 1) % 3] = i;
      M[i] = control_index(exponent[0], exponent[1], exponent[2]);
      if (i == 3) break;
      exponent[k] = 2 - i;
      exponent[(k + 2) % 3] = 1;
      L[i] = control_index(exponent[0], exponent[1], exponent[2]);
    }
    for (int i = 0; i < 3; ++i) {
      along[i] = patch[M[i + 1]] - patch[M[i]];
      across[i] = patch[L[i]] - patch[M[i]];
    }
  }
};

inline Eigen::Vector3d quadratic(const Eigen::Vector3d* b, double s) {
  const double t = 1.0 - s;
  return (t * t) * b[0] + (2.0 * s * t) * b[1] + (s * s) * b[2];
}

}  // namespace

G1Verification verify_g1(const BezierSurface& surface, int samples_per_edge) {
  const PatchAdjacency adjacency = patch_adjacency(surface);
  G1Verification result;
  result.shared_edges = adjacency.pairs.size();
  result.unmatched_edges = adjacency.unmatched;
  const int n = samples_per_edge + 1;
  // The largest angle is kept as its tangent too, so that the common case
  // (an angle at rounding level, below the largest so far) needs no atan2.
  double max_angle = 0.0, max_tangent = 0.0, max_squared_residual = 0.0;
  for (const PatchEdgePair& pair : adjacency.pairs) {
    const EdgeDerivatives P(surface.patches[pair.patch_a], pair.edge_a);
    const EdgeDerivatives Q(surface.patches[pair.patch_b], pair.edge_b);
    for (int i = 0; i <= n; ++i) {
      const double s = double(i) / n;
      const Eigen::Vector3d dP = quadratic(P.along, s), cP = quadratic(P.across, s);
      const Eigen::Vector3d dQ = quadratic(Q.along, 1.0 - s), cQ = quadratic(Q.across, 1.0 - s);
      const Eigen::Vector3d nP = dP.cross(cP), nQ = dQ.cross(cQ);
      // |[∇_d P, ∇_c P, ∇_c Q]| / (|∇_d P| |∇_c P| |∇_c Q|), squared.
      const double scale = dP.squaredNorm() * cP.squaredNorm() * cQ.squaredNorm();
      if (scale > 0.0) max_squared_residual = std::max(max_squared_residual, nP.dot(cQ) * nP.dot(cQ) / scale);
      ++result.samples;
      // A vanishing normal is a singular point: no tangent plane, not G¹.
      if (nP.squaredNorm() == 0.0 || nQ.squaredNorm() == 0.0) {
        max_angle = M_PI;
        max_tangent = INFINITY;
        continue;
      }
      const double sine = nP.cross(nQ).norm(), cosine = nP.dot(nQ);
      if (cosine > 0.0 && sine <= cosine * max_tangent) continue;
      const double angle = std::atan2(sine, cosine);
      if (angle > max_angle) {
        max_angle = angle;
        max_tangent = angle < M_PI / 2 ? std::tan(angle) : INFINITY;
      }
    }
  }
  result.max_normal_angle = max_angle;
  result.max_residual = std::sqrt(max_squared_residual);
  return result;
}

}  // namespace scanstation
