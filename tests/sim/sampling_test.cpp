#include "core/errors.h"
#include "core/mesh_measures.h"
#include "core/mesh_topology.h"
#include "core/polygon.h"
#include "core/self_intersections.h"
#include "sim/outlines.h"
#include "sim/relief_mask.h"
#include "sim/sampling.h"
#include "sim/shapes.h"
#include "test_support.h"

#include <Eigen/Geometry>
#include <cmath>

namespace scanstation::sim {
namespace {

// Distance from p to the segment ab.
double segment_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d d = b - a;
  const double t = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (a + t * d - p).norm();
}

double outline_distance(const Eigen::Vector2d& p, const Polygon2& outline) {
  double best = INFINITY;
  for (Eigen::Index i = 0; i < outline.size(); ++i)
    best = std::min(best, segment_distance(p, outline.vertices.row(i), outline.vertices.row((i + 1) % outline.size())));
  return best;
}

TEST(Outlines, ChaliceAndFaceAreSimpleCounterClockwise) {
  for (const int samples : {16, 61, 400}) {
    for (const Polygon2& outline : {chalice_outline(samples), face_profile_outline(samples)}) {
      EXPECT_TRUE(is_simple(outline)) << samples;
      EXPECT_GT(twice_signed_area(outline), 0.0) << samples;
      EXPECT_NEAR(static_cast<double>(outline.size()), samples, 1.0);
    }
  }
  // Resampling converges: the area of a fine face profile barely moves.
  const double fine = twice_signed_area(face_profile_outline(4000));
  EXPECT_NEAR(twice_signed_area(face_profile_outline(400)), fine, 2e-3 * fine);
  EXPECT_THROW(face_profile_outline(10), InvalidInput);
}

TEST(Outlines, FaceProfileHasConcavities) {
  // The nose bridge, mouth and chin crease make the outline non-convex: some
  // vertices turn clockwise although the outline runs counter-clockwise.
  const Polygon2 face = face_profile_outline(300);
  int reflex = 0;
  for (Eigen::Index i = 0; i < face.size(); ++i) {
    const Eigen::Vector2d a = face.vertices.row((i + face.size() - 1) % face.size()), b = face.vertices.row(i),
                          c = face.vertices.row((i + 1) % face.size());
    reflex += (b - a).x() * (c - b).y() - (b - a).y() * (c - b).x() < 0.0;
  }
  EXPECT_GT(reflex, 10);
}

TEST(ReliefMask, ClosedGenusZeroOutwardWithoutSelfIntersections) {
  const TriangleMesh mask = relief_mask(24, 64);
  EXPECT_EQ(mask.vertex_count(), 2 + (2 * 24 - 1) * 64);
  const MeshTopology t = mesh_topology(mask);
  EXPECT_TRUE(t.closed);
  EXPECT_TRUE(t.manifold);
  EXPECT_EQ(t.genus, 0);
  EXPECT_GT(enclosed_volume(mask.vertices.positions, mask.faces), 0.0);
  EXPECT_EQ(self_intersections(mask).value_or(1), 0u);
  // The nose stands out of the dome: the highest point is on the nose.
  Eigen::Index top;
  mask.vertices.positions.col(2).maxCoeff(&top);
  EXPECT_NEAR(mask.vertices.positions(top, 0), 0.0, 0.05);
  EXPECT_GT(relief_mask_height(0.0, -0.02), relief_mask_height(0.1, -0.02) + 0.05);
  EXPECT_EQ(relief_mask_height(0.8, 0.0), 0.0);
  EXPECT_THROW(relief_mask(1, 10), InvalidInput);
}

TEST(Sampling, SurfaceSamplesLieOnTheMeshAndAreReproducible) {
  const TriangleMesh sphere = icosphere(3);
  const PointCloud a = sample_surface(sphere, 2000, 7), b = sample_surface(sphere, 2000, 7);
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_NE(a.positions, sample_surface(sphere, 2000, 8).positions);
  // Every sample is inside the unit ball and outside the inscribed sphere of
  // the flat faces; its normal points away from the centre.
  const double inner = sphere.vertices.positions.rowwise().norm().minCoeff() * 0.98;
  for (Eigen::Index i = 0; i < a.size(); ++i) {
    EXPECT_LE(a.positions.row(i).norm(), 1.0 + 1e-12);
    EXPECT_GE(a.positions.row(i).norm(), inner);
    EXPECT_GT(a.positions.row(i).dot(a.normals.row(i)), 0.0);
  }
  // Area-uniform: each octant holds about an eighth of the samples.
  const PointCloud many = sample_surface(sphere, 80000, 3);
  const auto octant = (many.positions.col(0).array() > 0 && many.positions.col(1).array() > 0 &&
                       many.positions.col(2).array() > 0).count();
  EXPECT_NEAR(static_cast<double>(octant) / 80000.0, 0.125, 0.01);
}

TEST(Sampling, NoiseHasTheRequestedSpread) {
  const TriangleMesh sphere = icosphere(5);
  const PointCloud clean = sample_surface(sphere, 20000, 11), noisy = sample_surface(sphere, 20000, 11, 0.01);
  double sum = 0.0, sum2 = 0.0;
  for (Eigen::Index i = 0; i < clean.size(); ++i) {
    const double offset = (noisy.positions.row(i) - clean.positions.row(i)).dot(clean.normals.row(i));
    sum += offset;
    sum2 += offset * offset;
  }
  EXPECT_NEAR(sum / 20000.0, 0.0, 5e-4);
  EXPECT_NEAR(std::sqrt(sum2 / 20000.0), 0.01, 5e-4);
  const Eigen::MatrixXd moved = add_gaussian_noise(clean.positions, 0.02, 4);
  EXPECT_NEAR(std::sqrt((moved - clean.positions).squaredNorm() / (3.0 * 20000.0)), 0.02, 5e-4);
  EXPECT_THROW(sample_surface(sphere, 10, 1, -1.0), InvalidInput);
  EXPECT_THROW(sample_surface(TriangleMesh{}, 10, 1), InvalidInput);
}

TEST(Sampling, OutlineSamplesAreOnTheOutlineInBoundaryOrder) {
  const Polygon2 face = face_profile_outline(200);
  const Eigen::MatrixX2d points = sample_outline(face, 500, 9);
  for (Eigen::Index i = 0; i < points.rows(); ++i) EXPECT_LT(outline_distance(points.row(i), face), 1e-12);
  // In boundary order, so the samples themselves form a simple polygon.
  EXPECT_TRUE(is_simple(Polygon2{points}));
  const Eigen::MatrixX2d noisy = sample_outline(face, 500, 9, 0.002);
  double worst = 0.0;
  for (Eigen::Index i = 0; i < noisy.rows(); ++i) worst = std::max(worst, outline_distance(noisy.row(i), face));
  EXPECT_GT(worst, 0.002);
  EXPECT_LT(worst, 0.02);
}

}  // namespace
}  // namespace scanstation::sim
