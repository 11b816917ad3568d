#include "core/describe.h"
#include "core/mesh_measures.h"
#include "core/polygon.h"
#include "sim/shapes.h"
#include "test_support.h"

#include <cmath>
#include <numbers>

namespace scanstation {
namespace {

TEST(MeshMeasures, IcosphereApproachesTheUnitSphere) {
  const TriangleMesh sphere = sim::icosphere(5);
  EXPECT_NEAR(enclosed_volume(sphere.vertices.positions, sphere.faces), 4.0 / 3.0 * std::numbers::pi, 0.01);
  EXPECT_NEAR(surface_area(sphere.vertices.positions, sphere.faces), 4.0 * std::numbers::pi, 0.02);
  // Faces turned inwards: the same volume, negative.
  const Eigen::MatrixX3i inward = sphere.faces.rowwise().reverse();
  EXPECT_NEAR(enclosed_volume(sphere.vertices.positions, inward),
              -enclosed_volume(sphere.vertices.positions, sphere.faces), 1e-12);
}

// A scan far from the origin (turntable or scanner coordinates): the
// measures must not drown in the rounding of large terms.
TEST(MeshMeasures, VolumeAndAreaDoNotDependOnWhereTheMeshIs) {
  const TriangleMesh sphere = sim::icosphere(4);
  const double volume = enclosed_volume(sphere.vertices.positions, sphere.faces);
  const double area = surface_area(sphere.vertices.positions, sphere.faces);
  for (const Eigen::RowVector3d& offset : {Eigen::RowVector3d(1e6, -2e6, 3e5), Eigen::RowVector3d(-4e7, 0, 0)}) {
    const Eigen::MatrixX3d moved = sphere.vertices.positions.rowwise() + offset;
    EXPECT_NEAR(enclosed_volume(moved, sphere.faces), volume, 1e-7 * volume) << offset;
    EXPECT_NEAR(surface_area(moved, sphere.faces), area, 1e-7 * area) << offset;
  }
  EXPECT_EQ(enclosed_volume(sphere.vertices.positions, Eigen::MatrixX3i(0, 3)), 0.0);
}

// Scaled by a power of two, the measures scale exactly, as long as the
// result is a double: near 1e±160 the squares of the edge lengths left the
// range, and areas and diagonals that are ordinary doubles came out 0 or
// infinite.
TEST(MeshMeasures, ScaledByAPowerOfTwoTheMeasuresScaleExactly) {
  TriangleMesh sphere = sim::icosphere(3);
  const double area = surface_area(sphere.vertices.positions, sphere.faces);
  const double volume = enclosed_volume(sphere.vertices.positions, sphere.faces);
  const double diagonal = describe(sphere)["bounding_box"]["diagonal"];
  for (const int k : {-1000, -600, -300, 300, 600, 1000}) {
    const double s = std::ldexp(1.0, k);
    const Eigen::MatrixX3d V = sphere.vertices.positions * s;
    const auto expected = [](double x, int power) { return std::ldexp(x, power); };
    if (std::abs(2 * k) < 1000) {
      EXPECT_EQ(surface_area(V, sphere.faces), expected(area, 2 * k)) << k;
    }
    if (std::abs(3 * k) < 1000) {
      EXPECT_EQ(enclosed_volume(V, sphere.faces), expected(volume, 3 * k)) << k;
    }
    if (k < 0) {  // below the range: 0, not a wrong number
      EXPECT_GE(surface_area(V, sphere.faces), 0.0);
      EXPECT_GE(enclosed_volume(V, sphere.faces), 0.0);
    }
    TriangleMesh scaled = sphere;
    scaled.vertices.positions = V;
    EXPECT_EQ(describe(scaled)["bounding_box"]["diagonal"].get<double>(), expected(diagonal, k)) << k;
  }
  Polygon2 triangle;
  triangle.vertices.resize(3, 2);
  triangle.vertices << 0, 0, 3, 0, 0, 4;
  for (const int k : {-520, 520}) {
    Polygon2 scaled = triangle;
    scaled.vertices *= std::ldexp(1.0, k);
    EXPECT_EQ(twice_signed_area(scaled), std::ldexp(12.0, 2 * k)) << k;
    EXPECT_EQ(perimeter(scaled), std::ldexp(12.0, k)) << k;
  }
}

TEST(PolygonMeasures, AreaDoesNotDependOnWhereThePolygonIs) {
  Polygon2 square;
  square.vertices.resize(4, 2);
  square.vertices << 0, 0, 1, 0, 1, 1, 0, 1;
  for (const double offset : {0.0, 1e8, -3e12}) {
    Polygon2 moved = square;
    moved.vertices.array() += offset;
    EXPECT_EQ(twice_signed_area(moved), 2.0) << offset;
    moved.vertices = moved.vertices.colwise().reverse().eval();
    EXPECT_EQ(twice_signed_area(moved), -2.0) << offset;
  }
}

}  // namespace
}  // namespace scanstation
