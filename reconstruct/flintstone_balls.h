// The flintstone balls of a 3D approximation as a mesh, for inspection.
#pragma once

#include "reconstruct/flintstone_approximation.h"

namespace scanstation {

/// One coarse sphere (12 × 8 latitude-longitude triangles) per ball of each
/// approximating node's flintstone; half-spaces (Definition 7.5, radius −∞)
/// are left out. Vertex colours: red for B(v_q), blue for B(v_r).
TriangleMesh flintstone_balls_mesh(const FlintstoneTree3& tree, const MeshApproximation& approximation);

}  // namespace scanstation
