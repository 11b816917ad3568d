// Level-ℓ and adaptive flintstone approximations (thesis §7.2.2–7.2.3 and
// §7.3.2–7.3.3) with the errors of §6.2.
#pragma once

#include "reconstruct/flintstone_tree2.h"
#include "reconstruct/flintstone_tree3.h"

#include <vector>

namespace scanstation {

/// Errors of an approximation against the original:
///   e1  max distance of an original vertex to the approximation edge/triangle that replaces it (Error e1)
///   e2  the same to the edge's line / triangle's plane (Error e2)
///   e5  max flintstone width max{w1, w2} over the approximating pieces (Error e5, Definitions 7.4/7.6)
struct ApproximationErrors {
  double e1 = 0.0;
  double e2 = 0.0;
  double e5 = 0.0;
};

/// vertices  indices into the polygon's vertices, in boundary order
/// level     deepest tree level used
struct PolygonApproximation {
  std::vector<int> vertices;
  int level = 0;
  ApproximationErrors errors;
  std::vector<Chain2> pieces;  ///< the chain each approximation edge replaces
};

/// The level-ℓ approximation: levels 0 … ℓ of the tree (ℓ = 0: the edge v_i v_j twice).
PolygonApproximation approximation(const FlintstoneTree2& tree, int level);

/// The adaptive approximation: an edge is refined only while the width of its
/// flintstone (Error e5) exceeds `max_error`, so the result has e5 ≤ max_error.
PolygonApproximation adaptive_approximation(const FlintstoneTree2& tree, double max_error);

/// faces   #F by 3 triangles (indices into the tree's vertices) forming a
///         closed mesh: each approximating node contributes the triangulated
///         polygon of the marked vertices on its boundary — its corners
///         v_p v_s v_t plus the corners and side splits its neighbours use
///         there — so neighbours share their sides and nothing cracks
///         (§7.3.2); a void node (coalescing corners) may contribute nothing
/// pieces  the node each triangle approximates, same order
/// nodes   the approximating nodes (each once)
struct MeshApproximation {
  Eigen::MatrixX3i faces;
  int level = 0;
  ApproximationErrors errors;
  std::vector<int> pieces;
  std::vector<int> nodes;
};

/// Level-ℓ approximation in 3D: nodes down to depth ℓ + 1 (ℓ = 0: the root
/// triangle v_i v_j v_k for both halves). At the finest level it is the original.
MeshApproximation approximation(const FlintstoneTree3& tree, int level);

/// Adaptive approximation in 3D by Error e5 (Definition 7.6): e5 ≤ max_error.
MeshApproximation adaptive_approximation(const FlintstoneTree3& tree, double max_error);

}  // namespace scanstation
