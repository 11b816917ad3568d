// Self-intersections: the two-core split by a plane counts the pairs CGAL's
// one pass counts.
#include "core/self_intersections.h"
#include "core/errors.h"
#include "sim/shapes.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#include <gtest/gtest.h>

#include <algorithm>
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

// Faces known to meet one another properly (here: those of one sphere, or
// some of them) are not paired with each other, and the count stays CGAL's.
TEST(SelfIntersections, FacesThatMeetProperlyAreNotPairedAndTheCountStays) {
  for (const int subdivisions : {2, 4}) {  // one pass, and the split
    for (const Eigen::RowVector3d& offset : {Eigen::RowVector3d(1.0, 0, 0), Eigen::RowVector3d(0.05, 0, 0),
                                            Eigen::RowVector3d(0.3, 0.2, 0.1)}) {
      const TriangleMesh mesh = two_spheres(subdivisions, offset);
      const std::size_t expected = one_pass(mesh);
      ASSERT_GT(expected, 10u);
      const std::size_t half = static_cast<std::size_t>(mesh.face_count() / 2);
      std::vector<char> first_sphere(static_cast<std::size_t>(mesh.face_count()), 0);
      std::fill(first_sphere.begin(), first_sphere.begin() + static_cast<std::ptrdiff_t>(half), 1);
      EXPECT_EQ(self_intersections(mesh, first_sphere), std::optional<std::size_t>(expected)) << offset;
      std::vector<char> every_third(first_sphere.size(), 0);
      for (std::size_t f = 0; f < half; f += 3) every_third[f] = 1;
      EXPECT_EQ(self_intersections(mesh, every_third), std::optional<std::size_t>(expected)) << offset;
    }
  }
  // Every face vouched for: nothing is tested.
  const TriangleMesh crossing = two_spheres(2, Eigen::RowVector3d(0.5, 0, 0));
  EXPECT_EQ(self_intersections(crossing, std::vector<char>(static_cast<std::size_t>(crossing.face_count()), 1)),
            std::optional<std::size_t>(0));
  EXPECT_THROW(self_intersections(crossing, std::vector<char>(3, 1)), InvalidInput);
}

}  // namespace
}  // namespace scanstation
