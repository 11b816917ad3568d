// Vertex normals fitted to the points around each vertex, a scanstation
// extension of the thesis' §9.4. The weighted face normals of §9.4 see only
// a vertex's own triangles; on a scanned boundary a few of those lean far
// off the surface (long triangles across a sparsely scanned cap, where the
// boundary's connectivity is poor), and the G¹ surface bulges there. The
// normal of the plane fitted to the vertex's nearest neighbours in space
// (principal component analysis, as Open3D's and CGAL's point-set normal
// estimation) follows the sampled surface instead.
#pragma once

#include <Eigen/Core>

namespace scanstation {

/// V           #V by 3 vertex positions
/// F           #F by 3 faces, counter-clockwise from outside (closed,
///             oriented): they orient the normals
/// neighbours  how many nearest vertices (the vertex itself included) the
///             plane is fitted to; at least 3, at most #V
/// returns #V by 3 unit normals: at each vertex the normal of the least-
/// squares plane through those of its nearest vertices (a CGAL k-d tree)
/// that lie on the same side of the surface — their area-weighted face
/// normals (§9.4, method 1) less than 90° from its own — turned to the side
/// of its own; that face normal itself where fewer than three remain, where
/// they lie on one line, or where the fitted plane turns more than 45° from
/// it (the vertex's faces are not the sampled surface there: a hull face
/// over space the scan never saw, a sharp edge), and zero for a vertex in no
/// face, as vertex_normals gives. Throws InvalidInput for a neighbour count
/// out of range.
Eigen::MatrixX3d fitted_vertex_normals(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, int neighbours = 16);

class SameSideNeighbours;
/// The same with the neighbourhoods already indexed (same_side_neighbours.h);
/// neighbours is not checked.
Eigen::MatrixX3d fitted_vertex_normals(const Eigen::MatrixX3d& V, const SameSideNeighbours& around, int neighbours);

}  // namespace scanstation
