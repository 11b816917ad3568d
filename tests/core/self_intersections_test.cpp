// Self-intersections: the two-core split by a plane counts the pairs CGAL's
// one pass counts.
#include "core/self_intersections.h"
#include "sim/shapes.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#include <gtest/gtest.h>

#include <iterator>
#include <utility>
#include <vector>

namespace scanstation {
namespace {

std::size_t one_pass(const TriangleMesh& mesh) {
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
  Mesh sm;
  std::vector<Mesh::Vertex_index> v;
  for (Eigen::Index i = 0; i < mesh.vertex_count(); ++i)
    v.push_back(sm.add_vertex(Kernel::Point_3(mesh.vertices.positions(i, 0), mesh.vertices.positions(i, 1),
                                              mesh.vertices.positions(i, 2))));
  for (Eigen::Index f = 0; f < mesh.face_count(); ++f)
    sm.add_face(v[static_cast<std::size_t>(mesh.faces(f, 0))], v[static_cast<std::size_t>(mesh.faces(f, 1))],
                v[static_cast<std::size_t>(mesh.faces(f, 2))]);
  std::vector<std::pair<Mesh::Face_index, Mesh::Face_index>> pairs;
  CGAL::Polygon_mesh_processing::self_intersections(sm, std::back_inserter(pairs));
  return pairs.size();
}

// Two spheres in one mesh, the second moved by `offset`.
TriangleMesh two_spheres(int subdivisions, const Eigen::RowVector3d& offset) {
  const TriangleMesh s = sim::icosphere(subdivisions);
  TriangleMesh both;
  both.vertices.positions.resize(2 * s.vertex_count(), 3);
  both.vertices.positions << s.vertices.positions, s.vertices.positions.rowwise() + offset;
  both.faces.resize(2 * s.face_count(), 3);
  both.faces << s.faces, s.faces.array() + static_cast<int>(s.vertex_count());
  return both;
}

TEST(SelfIntersections, SplitAcrossTheCoresCountsWhatOnePassCounts) {
  // The circle where the spheres cross runs across the split plane (x at
  // the median face), along it (moved along y) and away from it.
  for (const Eigen::RowVector3d& offset : {Eigen::RowVector3d(1.0, 0, 0), Eigen::RowVector3d(0.3, 0.2, 0.1),
                                          Eigen::RowVector3d(0, 1.2, 0), Eigen::RowVector3d(0.05, 0, 0)}) {
    const TriangleMesh mesh = two_spheres(4, offset);
    ASSERT_GT(mesh.face_count(), 4096);  // the split is taken
    const std::size_t expected = one_pass(mesh);
    EXPECT_GT(expected, 100u);
    EXPECT_EQ(self_intersections(mesh), std::optional<std::size_t>(expected)) << offset;
  }
  const TriangleMesh apart = two_spheres(4, Eigen::RowVector3d(3.0, 0, 0));
  EXPECT_EQ(self_intersections(apart), std::optional<std::size_t>(0));
  EXPECT_EQ(self_intersections(sim::icosphere(5)), std::optional<std::size_t>(0));
}

}  // namespace
}  // namespace scanstation
