#include "smoothing/g1_verification.h"

#include "smoothing/blockwise.h"
#include "smoothing/normals_apart.h"
#include "smoothing/patch_adjacency.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

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

}  // namespace

G1Verification verify_g1(const BezierSurface& surface, int samples_per_edge) {
  const PatchAdjacency adjacency = patch_adjacency(surface);
  G1Verification result;
  result.shared_edges = adjacency.pairs.size();
  result.unmatched_edges = adjacency.unmatched;
  const int n = samples_per_edge + 1;
  // A dependent macro edge is joined by the closest solution of its
  // equations, and those also hold the split's inner edges at the macro
  // edge's midpoint (§9.8 Step 5: Z = (Y_a + Y_b)/2, the inner edges to O and
  // O' C¹): the patch edges on it and inside its two macro triangles need not
  // be G¹.
  std::vector<std::array<int, 2>> dependent = surface.dependent_edges;
  std::vector<int> near_dependent;
  for (const auto& [f, g] : dependent) near_dependent.insert(near_dependent.end(), {f, g});
  std::sort(dependent.begin(), dependent.end());
  std::sort(near_dependent.begin(), near_dependent.end());
  const auto approximate = [&](const PatchEdgePair& pair) {
    const int a = surface.macro[static_cast<std::size_t>(pair.patch_a)];
    const int b = surface.macro[static_cast<std::size_t>(pair.patch_b)];
    if (a == b) return std::binary_search(near_dependent.begin(), near_dependent.end(), a);
    return std::binary_search(dependent.begin(), dependent.end(), std::array<int, 2>{std::min(a, b), std::max(a, b)});
  };
  // Blocks of shared edges on all cores; only maxima and counts are
  // combined, so the answer does not depend on the split. Each block keeps
  // its largest angles as tangents too, so that the common case (an angle at
  // rounding level, below the largest so far) needs no atan2.
  constexpr std::size_t kBlock = 4096;
  struct Partial {
    double max_angle[2] = {0.0, 0.0}, max_tangent[2] = {0.0, 0.0}, max_squared_residual = 0.0;
    std::size_t samples = 0, folded_edges = 0;
  };
  const auto visit = [&](std::size_t begin, std::size_t end, Partial& part) {
    for (std::size_t e = begin; e < end; ++e) {
      const PatchEdgePair& pair = adjacency.pairs[e];
      const int kind = approximate(pair) ? 1 : 0;  // 0: joined exactly
      const EdgeDerivatives P(surface.patches[pair.patch_a], pair.edge_a);
      const EdgeDerivatives Q(surface.patches[pair.patch_b], pair.edge_b);
      // A fold, however narrow, that the samples may step over.
      if (reaches_zero(cross_product(P.along, P.across), reversed(cross_product(Q.along, Q.across)))) {
        ++part.folded_edges;
        part.max_angle[kind] = M_PI;
        part.max_tangent[kind] = INFINITY;
      }
      for (int i = 0; i <= n; ++i) {
        const double s = double(i) / n;
        const Eigen::Vector3d dP = quadratic(P.along, s), cP = quadratic(P.across, s);
        const Eigen::Vector3d dQ = quadratic(Q.along, 1.0 - s), cQ = quadratic(Q.across, 1.0 - s);
        const Eigen::Vector3d nP = dP.cross(cP), nQ = dQ.cross(cQ);
        // |[∇_d P, ∇_c P, ∇_c Q]| / (|∇_d P| |∇_c P| |∇_c Q|), squared.
        const double scale = dP.squaredNorm() * cP.squaredNorm() * cQ.squaredNorm();
        if (scale > 0.0) part.max_squared_residual = std::max(part.max_squared_residual, nP.dot(cQ) * nP.dot(cQ) / scale);
        ++part.samples;
        // A vanishing normal is a singular point: no tangent plane, not G¹.
        if (nP.squaredNorm() == 0.0 || nQ.squaredNorm() == 0.0) {
          part.max_angle[kind] = M_PI;
          part.max_tangent[kind] = INFINITY;
          continue;
        }
        const double sine = nP.cross(nQ).norm(), cosine = nP.dot(nQ);
        if (cosine > 0.0 && sine <= cosine * part.max_tangent[kind]) continue;
        const double angle = std::atan2(sine, cosine);
        if (angle > part.max_angle[kind]) {
          part.max_angle[kind] = angle;
          part.max_tangent[kind] = angle < M_PI / 2 ? std::tan(angle) : INFINITY;
        }
      }
    }
  };
  const auto partial = blockwise<Partial>(adjacency.pairs.size(), kBlock, visit);
  double max_angle[2] = {0.0, 0.0}, max_squared_residual = 0.0;
  for (const Partial& part : partial) {
    for (int kind = 0; kind < 2; ++kind) max_angle[kind] = std::max(max_angle[kind], part.max_angle[kind]);
    max_squared_residual = std::max(max_squared_residual, part.max_squared_residual);
    result.samples += part.samples;
    result.folded_edges += part.folded_edges;
  }
  result.max_normal_angle = std::max(max_angle[0], max_angle[1]);
  result.max_normal_angle_exact = max_angle[0];
  result.max_residual = std::sqrt(max_squared_residual);
  return result;
}

}  // namespace scanstation
