// Geometric simplicity of a triangle mesh, decided with exact predicates.
#pragma once

#include "core/triangle_mesh.h"

#include <cstddef>
#include <optional>

namespace scanstation {

/// The number of pairs of faces that meet anywhere but in the vertices and
/// edges they share (CGAL Polygon Mesh Processing, exact predicates): 0 for
/// a simple surface. nullopt when the faces do not form an oriented
/// 2-manifold that a halfedge structure can hold (check mesh_topology first).
std::optional<std::size_t> self_intersections(const TriangleMesh& mesh);

}  // namespace scanstation
