// Edge adjacency of a closed, consistently oriented triangle mesh: the
// neighbour across each triangle edge, as the splitting schemes need it.
#pragma once

#include <Eigen/Core>

namespace scanstation {

/// F #F by 3 triangles. Edge e of face f runs from corner e to corner (e+1)%3.
/// neighbour(f, e)  the face on the other side of that edge
/// neighbour_edge(f, e)  that edge's local index in the neighbour face
struct MeshEdges {
  Eigen::MatrixX3i neighbour;
  Eigen::MatrixX3i neighbour_edge;
};

/// Throws TopologyError naming an edge that is not shared by exactly two
/// faces in opposite directions (the surface must be closed, manifold and
/// oriented, as constriction produces it), or a vertex whose faces form more
/// than one fan (a pinch: two surfaces sharing the vertex).
MeshEdges mesh_edges(const Eigen::MatrixX3i& F);

}  // namespace scanstation
