#include "core/self_intersections.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <iterator>
#include <vector>

namespace scanstation {

std::optional<std::size_t> self_intersections(const TriangleMesh& mesh) {
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
  Mesh sm;
  std::vector<Mesh::Vertex_index> vertex;
  vertex.reserve(static_cast<std::size_t>(mesh.vertex_count()));
  const auto& P = mesh.vertices.positions;
  for (Eigen::Index i = 0; i < P.rows(); ++i) vertex.push_back(sm.add_vertex(Kernel::Point_3(P(i, 0), P(i, 1), P(i, 2))));
  for (Eigen::Index f = 0; f < mesh.face_count(); ++f) {
    const auto face = sm.add_face(vertex[static_cast<std::size_t>(mesh.faces(f, 0))],
                                  vertex[static_cast<std::size_t>(mesh.faces(f, 1))],
                                  vertex[static_cast<std::size_t>(mesh.faces(f, 2))]);
    if (face == Mesh::null_face()) return std::nullopt;
  }
  std::vector<std::pair<Mesh::Face_index, Mesh::Face_index>> pairs;
  CGAL::Polygon_mesh_processing::self_intersections(sm, std::back_inserter(pairs));
  return pairs.size();
}

}  // namespace scanstation
