// Hierarchical intersection (thesis §7.4) against brute-force all-pairs tests.
#include "core/io/mesh_io.h"
#include "reconstruct/flintstone_intersection.h"
#include "sim/random.h"
#include "sim/shapes.h"
#include "test_support.h"

#include <Eigen/Geometry>
#include <numbers>

namespace scanstation {
namespace {

Polygon2 wiggly_polygon(int n, double phase, const Eigen::Vector2d& center, double radius) {
  Polygon2 polygon;
  polygon.vertices.resize(n, 2);
  for (int k = 0; k < n; ++k) {
    const double angle = 2.0 * std::numbers::pi * k / n;
    const double r = radius * (1.0 + 0.25 * std::sin(7.0 * angle + phase));
    polygon.vertices.row(k) = (center + r * Eigen::Vector2d(std::cos(angle), std::sin(angle))).transpose();
  }
  return polygon;
}

TriangleMesh moved(TriangleMesh mesh, const Eigen::Matrix3d& rotation, const Eigen::Vector3d& offset, double scale = 1.0) {
  mesh.vertices.positions = ((mesh.vertices.positions * rotation.transpose()) * scale).rowwise() + offset.transpose();
  return mesh;
}

TEST(FlintstoneIntersection2, PairsMatchBruteForce) {
  const Polygon2 a = wiggly_polygon(180, 0.0, {0, 0}, 1.0);
  for (const double dx : {0.3, 1.2, 2.1, 5.0}) {
    const Polygon2 b = wiggly_polygon(150, 1.3, {dx, 0.1}, 0.9);
    const FlintstoneTree2 ta = flintstone_tree(a), tb = flintstone_tree(b);
    IntersectionStats stats;
    const auto pairs = intersecting_edges(ta, tb, false, &stats);
    const auto expected = intersecting_edges_brute_force(a.vertices, b.vertices);
    EXPECT_EQ(pairs, expected) << "dx " << dx;
    EXPECT_EQ(intersecting_edges(ta, tb, true).empty(), expected.empty()) << "dx " << dx;
    if (dx < 5.0) {
      EXPECT_FALSE(expected.empty()) << dx;
    }
    EXPECT_LT(stats.exact_tests, static_cast<std::size_t>(180 * 150) / 4) << "dx " << dx;
  }
}

TEST(FlintstoneIntersection3, PairsMatchBruteForce) {
  const TriangleMesh sphere = sim::icosphere(2);
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  for (const double dx : {0.2, 1.0, 1.9, 2.5}) {
    const TriangleMesh other = moved(sim::ellipsoid({1.0, 0.6, 0.8}, 2), turn, {dx, 0.1, -0.05});
    const FlintstoneTree3 ta = flintstone_tree(sphere), tb = flintstone_tree(other);
    IntersectionStats stats;
    const auto pairs = intersecting_faces(ta, tb, false, &stats);
    const auto expected = intersecting_faces_brute_force(sphere, other);
    EXPECT_EQ(pairs, expected) << "dx " << dx;
    EXPECT_EQ(intersecting_faces(ta, tb, true).empty(), expected.empty()) << "dx " << dx;
    EXPECT_EQ(solids_intersect(ta, tb), !expected.empty()) << "dx " << dx;
    EXPECT_LT(stats.exact_tests, static_cast<std::size_t>(sphere.face_count() * other.face_count()) / 10);
  }
}

TEST(FlintstoneIntersection3, NestedTouchingAndRealMeshes) {
  const TriangleMesh sphere = sim::icosphere(2);
  const FlintstoneTree3 outer = flintstone_tree(sphere);
  // Nested: no faces meet, but the solids do.
  const FlintstoneTree3 inner = flintstone_tree(moved(sphere, Eigen::Matrix3d::Identity(), {0.1, 0, 0}, 0.5));
  EXPECT_TRUE(intersecting_faces(outer, inner).empty());
  EXPECT_TRUE(solids_intersect(outer, inner));
  EXPECT_TRUE(solids_intersect(inner, outer));
  // Touching at exactly one vertex: (1,0,0)-ish vertex of the icosphere mirrored.
  TriangleMesh mirrored = sphere;
  const Eigen::Vector3d v = sphere.vertices.positions.row(0).transpose();
  mirrored.vertices.positions = (-sphere.vertices.positions).rowwise() + (2.0 * v).transpose();
  mirrored.faces.col(1).swap(mirrored.faces.col(2));  // keep it outward after the point reflection
  const auto touching = intersecting_faces(outer, flintstone_tree(mirrored));
  EXPECT_EQ(touching, intersecting_faces_brute_force(sphere, mirrored));
  EXPECT_FALSE(touching.empty());
  // A real mesh against a turned copy of itself.
  const TriangleMesh cube = io::read_mesh(test::cgal_data("meshes/cube.off"));
  const TriangleMesh turned =
      moved(cube, Eigen::AngleAxisd(0.5, Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix(), {0.3, 0.2, 0.1});
  EXPECT_EQ(intersecting_faces(flintstone_tree(cube), flintstone_tree(turned)), intersecting_faces_brute_force(cube, turned));
}

}  // namespace
}  // namespace scanstation
