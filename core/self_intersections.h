// Geometric simplicity of a triangle mesh, decided with exact predicates.
#pragma once

#include "core/triangle_mesh.h"

#include <cstddef>
#include <optional>
#include <vector>

namespace scanstation {

/// The number of pairs of faces that meet anywhere but in the vertices and
/// edges they share (CGAL Polygon Mesh Processing, exact predicates): 0 for
/// a simple surface. nullopt when the faces do not form an oriented
/// 2-manifold that a halfedge structure can hold (check mesh_topology first).
///
/// meet_properly  empty, or one flag per face: 1 for faces known to meet one
///                another only in shared vertices and edges — facets of one
///                triangulation, such as the Delaunay facets a reconstruction
///                keeps. No pair of two flagged faces is tested: only the
///                faces whose bounding boxes meet an unflagged face's take
///                part, and with every face flagged the answer is 0 at once
///                (the caller vouches for the faces).
std::optional<std::size_t> self_intersections(const TriangleMesh& mesh, const std::vector<char>& meet_properly = {});

}  // namespace scanstation
