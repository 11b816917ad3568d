// A triangulated disk judged by its shadow on a coordinate plane
// (reconstruct/shadow_embedding.h): whenever the shadow says the faces meet
// only in shared corners and edges, CGAL's exact self-intersection test
// agrees; disks folded over themselves are never passed.
#include "core/self_intersections.h"
#include "core/triangle_mesh.h"
#include "reconstruct/delaunay_complex.h"
#include "reconstruct/shadow_embedding.h"
#include "sim/random.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <string>
#include <vector>

namespace scanstation {
namespace {

struct Disk {
  Eigen::MatrixX3d P;
  std::vector<std::array<int, 3>> faces;  // counter-clockwise seen from +normal
  std::vector<int> loop;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
};

// A disk of well-shaped triangles: 24 points on the unit circle and a
// jittered grid of spacing 0.2 inside radius 0.8, each lifted by `bumps`
// times a standard normal, joined by the Delaunay triangulation of their
// plan (z = 0 up).
Disk random_disk(sim::Random& random, double bumps) {
  Disk disk;
  std::vector<Eigen::Vector2d> points;
  for (int k = 0; k < 24; ++k) {
    const double a = (k + random.uniform(-0.2, 0.2)) * 2.0 * std::numbers::pi / 24.0;
    points.emplace_back(std::cos(a), std::sin(a));
  }
  for (double x = -0.8; x <= 0.8; x += 0.2)
    for (double y = -0.8; y <= 0.8; y += 0.2)
      if (x * x + y * y <= 0.64) points.emplace_back(x + random.uniform(-0.05, 0.05), y + random.uniform(-0.05, 0.05));
  const auto n = static_cast<Eigen::Index>(points.size());
  Eigen::MatrixX2d plan(n, 2);
  for (Eigen::Index i = 0; i < n; ++i) plan.row(i) = points[static_cast<std::size_t>(i)].transpose();
  disk.P.resize(n, 3);
  for (Eigen::Index i = 0; i < n; ++i) disk.P.row(i) << plan(i, 0), plan(i, 1), bumps * random.normal();
  const DelaunayComplex<2> dt = delaunay_complex(plan);
  for (Eigen::Index c = 0; c < dt.cells.rows(); ++c) {
    std::array<int, 3> t{dt.cells(c, 0), dt.cells(c, 1), dt.cells(c, 2)};
    const Eigen::Vector2d a = plan.row(t[0]), b = plan.row(t[1]), d = plan.row(t[2]);
    const Eigen::Vector2d u = b - a, v = d - a;
    if (u.x() * v.y() - u.y() * v.x() < 0) std::swap(t[1], t[2]);
    disk.faces.push_back(t);
  }
  // The loop: the directed edges whose reverse no face has, by their start.
  std::map<std::pair<int, int>, int> directed;
  for (const auto& t : disk.faces)
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  std::map<int, int> next;
  for (const auto& [e, count] : directed)
    if (!directed.count({e.second, e.first})) next[e.first] = e.second;
  disk.loop.push_back(next.begin()->first);
  while (next[disk.loop.back()] != disk.loop.front()) disk.loop.push_back(next[disk.loop.back()]);
  EXPECT_EQ(disk.loop.size(), next.size());
  return disk;
}

// The disk turned by `degrees` about an axis in the plane z = 0.
void tilt(Disk& disk, double degrees, double axis_degrees) {
  const double a = axis_degrees * std::numbers::pi / 180.0;
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(degrees * std::numbers::pi / 180.0, Eigen::Vector3d(std::cos(a), std::sin(a), 0.0))
          .toRotationMatrix();
  disk.P = (disk.P * R.transpose()).eval();
  disk.normal = R * disk.normal;
}

std::size_t crossings(const Disk& disk) {
  TriangleMesh mesh;
  mesh.vertices.positions = disk.P;
  mesh.faces.resize(static_cast<Eigen::Index>(disk.faces.size()), 3);
  for (std::size_t f = 0; f < disk.faces.size(); ++f)
    mesh.faces.row(static_cast<Eigen::Index>(f)) << disk.faces[f][0], disk.faces[f][1], disk.faces[f][2];
  const auto count = self_intersections(mesh);
  EXPECT_TRUE(count.has_value());
  return count.value_or(0);
}

TEST(ShadowEmbedding, AHeightFieldIsPassedUpToATiltPastTheDiagonalAndNotUpsideDown) {
  sim::Random random(11);
  for (const double degrees : {0.0, 30.0, 60.0, 89.0, 135.0}) {
    Disk disk = random_disk(random, 0.01);
    tilt(disk, degrees, 20.0);
    // Past 54.7° another coordinate plane is the shadow's (and the normal
    // points down one of its axes): still a graph over it.
    EXPECT_TRUE(embedded_over_axis(disk.P, disk.faces, disk.loop, disk.normal)) << degrees << "°";
    EXPECT_FALSE(embedded_over_axis(disk.P, disk.faces, disk.loop, -disk.normal)) << degrees << "°, reversed";
  }
}

TEST(ShadowEmbedding, NeverPassesAFoldedDisk) {
  // Inner points pushed across their neighbours fold the disk over itself
  // (nearly flat, so the folded faces cross), or only distort it: whenever
  // the shadow passes the disk, no two faces meet improperly.
  sim::Random random(7);
  int passed = 0, crossed = 0;
  for (int trial = 0; trial < 200; ++trial) {
    Disk disk = random_disk(random, 0.01);
    const auto n = static_cast<int>(disk.P.rows());
    for (int k = 0; k < 3; ++k) {
      const int v = std::min(n - 1, static_cast<int>(random.uniform(0.0, n)));
      if (std::find(disk.loop.begin(), disk.loop.end(), v) != disk.loop.end()) continue;
      disk.P(v, 0) += random.uniform(-0.3, 0.3);
      disk.P(v, 1) += random.uniform(-0.3, 0.3);
    }
    tilt(disk, random.uniform(0.0, 180.0), random.uniform(0.0, 360.0));
    const bool embedded = embedded_over_axis(disk.P, disk.faces, disk.loop, disk.normal);
    const std::size_t met = crossings(disk);
    if (embedded) {
      EXPECT_EQ(met, 0u) << "trial " << trial;
    }
    passed += embedded;
    crossed += met > 0;
  }
  EXPECT_GT(passed, 20);  // neither half of the check is empty
  EXPECT_GT(crossed, 20);
}

TEST(ShadowEmbedding, AFlatStripWoundTwiceIsNotPassed) {
  // Every face turns the right way, but the strip covers its annulus twice:
  // only the loop's shadow, not simple, tells (and the faces do cross).
  constexpr int kSteps = 41;  // odd: no two points of the two turns coincide
  Disk strip;
  strip.P.resize(2 * (kSteps + 1), 3);
  for (int k = 0; k <= kSteps; ++k) {
    const double a = 4.0 * std::numbers::pi * k / kSteps;
    strip.P.row(2 * k) << 0.5 * std::cos(a), 0.5 * std::sin(a), 0.0;
    strip.P.row(2 * k + 1) << std::cos(a), std::sin(a), 0.0;
  }
  for (int k = 0; k < kSteps; ++k) {
    strip.faces.push_back({2 * k, 2 * k + 1, 2 * k + 3});
    strip.faces.push_back({2 * k, 2 * k + 3, 2 * k + 2});
  }
  for (int k = 0; k <= kSteps; ++k) strip.loop.push_back(2 * k + 1);      // out along the outer edge
  for (int k = kSteps; k >= 0; --k) strip.loop.push_back(2 * k);          // back along the inner one
  EXPECT_FALSE(embedded_over_axis(strip.P, strip.faces, strip.loop, strip.normal));
  EXPECT_GT(crossings(strip), 0u);
  // One turn of it (half the steps) is a disk over its shadow.
  Disk half = strip;
  half.faces.resize(kSteps - 1);  // the first 20 steps, two faces each
  half.loop.clear();
  const int steps = (kSteps - 1) / 2;
  for (int k = 0; k <= steps; ++k) half.loop.push_back(2 * k + 1);
  for (int k = steps; k >= 0; --k) half.loop.push_back(2 * k);
  EXPECT_TRUE(embedded_over_axis(half.P, half.faces, half.loop, half.normal));
}

TEST(ShadowEmbedding, DegenerateInputsAreNotPassed) {
  sim::Random random(3);
  Disk disk = random_disk(random, 0.0);
  EXPECT_TRUE(embedded_over_axis(disk.P, disk.faces, disk.loop, disk.normal));
  EXPECT_FALSE(embedded_over_axis(disk.P, disk.faces, disk.loop, Eigen::Vector3d::Zero()));
  // A face flat in the shadow: one point moved onto the line of two others.
  Disk flat = disk;
  const auto& t = flat.faces.front();
  flat.P.row(t[2]) = 0.5 * (flat.P.row(t[0]) + flat.P.row(t[1]));
  EXPECT_FALSE(embedded_over_axis(flat.P, flat.faces, flat.loop, flat.normal));
}

}  // namespace
}  // namespace scanstation
