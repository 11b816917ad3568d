#include "core/errors.h"
#include "core/mesh_measures.h"
#include "core/mesh_topology.h"
#include "core/polygon.h"
#include "sim/random.h"
#include "sim/shapes.h"
#include "sim/surface_of_revolution.h"
#include "test_support.h"

#include <Eigen/Geometry>
#include <numbers>

namespace scanstation::sim {
namespace {

double signed_volume(const TriangleMesh& m) { return enclosed_volume(m.vertices.positions, m.faces); }

TEST(Shapes, IcosphereConvergesToTheSphereOutwardOriented) {
  for (int s = 0; s <= 4; ++s) {
    const TriangleMesh m = icosphere(s);
    EXPECT_EQ(m.vertex_count(), 10 * (1 << (2 * s)) + 2);
    EXPECT_NEAR(m.vertices.positions.rowwise().norm().minCoeff(), 1.0, 1e-12);
    EXPECT_GT(signed_volume(m), 0.0);
  }
  EXPECT_NEAR(signed_volume(icosphere(5)), 4.0 / 3.0 * std::numbers::pi, 0.01);
  const TriangleMesh e = ellipsoid({1, 2, 3}, 5);
  EXPECT_NEAR(signed_volume(e), 4.0 / 3.0 * std::numbers::pi * 6.0, 0.06);
}

TEST(Shapes, TorusVolume) {
  const TriangleMesh t = torus(2.0, 0.5, 128, 64);
  EXPECT_NEAR(signed_volume(t), 2.0 * std::numbers::pi * std::numbers::pi * 2.0 * 0.25, 0.05);
  EXPECT_EQ(mesh_topology(t).genus, 1);
}

// Pappus: the volume of a solid of revolution is 2π·(first moment of the
// profile region about the axis); the mesh must converge to it.
TEST(Shapes, ChaliceIsAClosedGenusZeroSolidOfTheRightVolume) {
  const Eigen::MatrixX2d profile = chalice_profile(400);
  Polygon2 region;
  region.vertices = profile;  // closed along the axis from the top pole back to the bottom
  EXPECT_TRUE(is_simple(region));
  double moment = 0.0;  // ∫∫ r dA over the region, by the shoelace-style formula
  for (Eigen::Index i = 0; i < profile.rows(); ++i) {
    const Eigen::RowVector2d p = profile.row(i), q = profile.row((i + 1) % profile.rows());
    moment += (p.x() * q.y() - q.x() * p.y()) * (p.x() + q.x()) / 6.0;
  }
  const double pappus = 2.0 * std::numbers::pi * std::abs(moment);
  const TriangleMesh chalice = surface_of_revolution(profile, 256);
  const MeshTopology t = mesh_topology(chalice);
  EXPECT_TRUE(t.closed && t.manifold && t.oriented);
  EXPECT_EQ(t.genus, 0);
  EXPECT_NEAR(signed_volume(chalice), pappus, 0.002 * pappus);
}

TEST(Shapes, CandlestickIsAClosedGenusZeroSolid) {
  const TriangleMesh c = surface_of_revolution(candlestick_profile(200), 64);
  const MeshTopology t = mesh_topology(c);
  EXPECT_TRUE(t.closed && t.manifold && t.oriented);
  EXPECT_EQ(t.genus, 0);
  EXPECT_GT(signed_volume(c), 0.5);
  EXPECT_LT(signed_volume(c), std::numbers::pi * 0.8 * 0.8 * 2.3);  // inside its bounding cylinder
  EXPECT_THROW(candlestick_profile(3), InvalidInput);
}

TEST(Shapes, BadParametersAreRejected) {
  Eigen::MatrixX2d open(3, 2);
  open << 0, 0, 1, 0.5, 0.5, 1;  // does not end on the axis
  EXPECT_THROW(surface_of_revolution(open, 8), InvalidInput);
  EXPECT_THROW(surface_of_revolution(chalice_profile(20), 2), InvalidInput);
  EXPECT_THROW(icosphere(-1), InvalidInput);
}

// mt19937_64 is specified to the bit; so must be what we derive from it.
TEST(Random, SameSequenceEverywhere) {
  Random a(42), b(42), c(43);
  for (int i = 0; i < 100; ++i) {
    const double x = a.uniform();
    EXPECT_EQ(x, b.uniform());
    EXPECT_GE(x, 0.0);
    EXPECT_LT(x, 1.0);
  }
  EXPECT_NE(Random(42).uniform(), c.uniform());
  // The C++ standard fixes the 10000th output of a default-seeded mt19937_64.
  std::mt19937_64 engine;
  engine.discard(9999);
  EXPECT_EQ(engine(), 9981545732273789042ULL);
  double sum = 0.0, squares = 0.0;
  Random n(1);
  for (int i = 0; i < 100000; ++i) {
    const double z = n.normal();
    sum += z;
    squares += z * z;
  }
  EXPECT_NEAR(sum / 100000, 0.0, 0.02);
  EXPECT_NEAR(squares / 100000, 1.0, 0.02);
}

}  // namespace
}  // namespace scanstation::sim
