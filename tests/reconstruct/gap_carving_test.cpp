// Gap carving: the cells reached from outside through wide faces, against a
// brute force; that it stays out of sampled solids; and what it recovers.
#include "reconstruct/gap_carving.h"

#include "core/errors.h"
#include "core/io/mesh_io.h"
#include "core/triangle_recall.h"
#include "reconstruct/boundary_reconstruction.h"
#include "reconstruct/delaunay_complex.h"
#include "sim/random.h"
#include "sim/sampling.h"
#include "sim/shapes.h"
#include "test_support.h"
#include "valid_surface.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <set>

namespace scanstation {
namespace {

// The reference: spacing from the sorted distinct lengths of each point's
// edges (collected in a set), the smallest ball from the angles and the
// circumcentre, the depths and parts by relaxing until nothing changes.
// Returns false when a face lies too close to the width limit for two
// formulas to agree on it.
bool reference_depths(const DelaunayComplex<3>& dt, const GapOptions& options, std::vector<int>& depth) {
  std::set<std::pair<int, int>> edges;
  for (Eigen::Index c = 0; c < dt.cells.rows(); ++c)
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j)
        if (i != j) edges.emplace(dt.cells(c, i), dt.cells(c, j));
  std::map<int, std::vector<double>> lengths;
  for (const auto& [a, b] : edges) lengths[a].push_back((dt.points.row(a) - dt.points.row(b)).norm());
  std::map<int, double> spacing;
  for (auto& [v, l] : lengths) {
    std::sort(l.begin(), l.end());
    l.erase(std::unique(l.begin(), l.end()), l.end());
    spacing[v] = l[std::min(l.size(), static_cast<std::size_t>(options.neighbour)) - 1];
  }
  bool decided = true;
  const auto wide = [&](Eigen::Index c, int i) {
    Eigen::Vector3d p[3];
    double local = 0;
    for (int k = 0, n = 0; k < 4; ++k)
      if (k != i) {
        p[n++] = dt.points.row(dt.cells(c, k)).transpose();
        local = std::max(local, spacing[dt.cells(c, k)]);
      }
    // The smallest ball holding the face: on its longest edge when an angle
    // is 90° or more, else the circumscribed one.
    double radius = -1;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d& q = p[k];
      const Eigen::Vector3d& r = p[(k + 1) % 3];
      const Eigen::Vector3d& s = p[(k + 2) % 3];
      if ((r - q).dot(s - q) <= 0) radius = 0.5 * (s - r).norm();
    }
    if (radius < 0) {
      const Eigen::Vector3d u = p[1] - p[0], w = p[2] - p[0], n = u.cross(w);
      const Eigen::Vector3d centre =
          p[0] + (u.squaredNorm() * w.cross(n) + w.squaredNorm() * n.cross(u)) / (2 * n.squaredNorm());
      radius = (centre - p[0]).norm();
    }
    const double ratio = radius / (options.width * local);
    if (std::abs(ratio - 1) < 1e-9) decided = false;
    return ratio > 1;
  };
  depth.assign(static_cast<std::size_t>(dt.cells.rows()), -1);
  for (Eigen::Index c = 0; c < dt.cells.rows(); ++c)
    for (int i = 0; i < 4; ++i)
      if (dt.neighbors(c, i) < 0 && wide(c, i)) depth[static_cast<std::size_t>(c)] = 0;
  for (bool changed = true; changed;) {
    changed = false;
    for (Eigen::Index c = 0; c < dt.cells.rows(); ++c) {
      const int d = depth[static_cast<std::size_t>(c)];
      if (d < 0) continue;
      for (int i = 0; i < 4; ++i) {
        const int n = dt.neighbors(c, i);
        if (n < 0 || !wide(c, i)) continue;
        int& e = depth[static_cast<std::size_t>(n)];
        if (e < 0 || e > d + 1) {
          e = d + 1;
          changed = true;
        }
      }
    }
  }
  // Parts: every reached cell labelled with the smallest cell of its part,
  // by relaxing labels across wide faces; then each part's deepest cell.
  std::vector<Eigen::Index> label(depth.size());
  for (std::size_t c = 0; c < label.size(); ++c) label[c] = static_cast<Eigen::Index>(c);
  for (bool changed = true; changed;) {
    changed = false;
    for (Eigen::Index c = 0; c < dt.cells.rows(); ++c)
      for (int i = 0; i < 4; ++i) {
        const int n = dt.neighbors(c, i);
        if (n < 0 || depth[static_cast<std::size_t>(c)] < 0 || depth[static_cast<std::size_t>(n)] < 0 || !wide(c, i)) continue;
        const Eigen::Index low = std::min(label[static_cast<std::size_t>(c)], label[static_cast<std::size_t>(n)]);
        if (label[static_cast<std::size_t>(c)] != low || label[static_cast<std::size_t>(n)] != low) {
          label[static_cast<std::size_t>(c)] = label[static_cast<std::size_t>(n)] = low;
          changed = true;
        }
      }
  }
  std::map<Eigen::Index, int> deepest;
  for (std::size_t c = 0; c < depth.size(); ++c)
    if (depth[c] >= 0) deepest[label[c]] = std::max(deepest[label[c]], depth[c]);
  for (std::size_t c = 0; c < depth.size(); ++c)
    if (depth[c] >= 0 && deepest[label[c]] < options.depth) depth[c] = -1;
  return decided;
}

TEST(GapCarving, DepthsMatchABruteForce) {
  int compared = 0, reached = 0;
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    sim::Random random(seed);
    // Two clusters apart, and a uniform cube: gaps of every width.
    Eigen::MatrixX3d P(50, 3);
    for (Eigen::Index i = 0; i < P.rows(); ++i) {
      const double shift = seed % 2 == 0 && i % 2 == 0 ? 3.0 : 0.0;
      P.row(i) << random.uniform() + shift, random.uniform(), random.uniform();
    }
    const DelaunayComplex<3> dt = delaunay_complex(P);
    for (const int neighbour : {1, 3, 5, 40})
      for (const double width : {0.7, 1.0, 2.0, 4.0})
        for (const int least : {0, 2, 5}) {
          const GapOptions options{neighbour, width, least};
          std::vector<int> expected;
          if (!reference_depths(dt, options, expected)) continue;
          const std::vector<int> depth = gap_depths(dt, options);
          EXPECT_EQ(depth, expected) << "seed " << seed << " neighbour " << neighbour << " width " << width << " depth "
                                     << least;
          ++compared;
          reached += std::count_if(depth.begin(), depth.end(), [](int d) { return d > 0; }) > 0;
        }
  }
  EXPECT_GT(compared, 400);
  EXPECT_GT(reached, 20);  // the walk went beyond the hull's cells
}

TEST(GapCarving, RejectsBadOptions) {
  Eigen::MatrixX3d P(4, 3);
  P << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  const DelaunayComplex<3> dt = delaunay_complex(P);
  test::expect_error<InvalidInput>([&] { gap_depths(dt, {0, 4.0}); }, {"neighbour"});
  test::expect_error<InvalidInput>([&] { gap_depths(dt, {5, NAN}); }, {"width"});
  test::expect_error<InvalidInput>([&] { gap_depths(dt, {5, 4.0, -1}); }, {"depth"});
}

TEST(GapCarving, CarveOrderKeepsTheFirstRanksFirst) {
  EXPECT_EQ(carve_first_then({-1, 0, 2, -1, -1}, {0, 1, -1, 3, -1}), (std::vector<int>{3, 0, 2, 6, -1}));
  EXPECT_EQ(carve_first_then({}, {-1, 2}), (std::vector<int>{-1, 2}));
  EXPECT_EQ(carve_first_then({1, -1}, {}), (std::vector<int>{1, -1}));
  EXPECT_TRUE(carve_first_then({-1, -1}, {-1, -1}).empty());
  EXPECT_TRUE(carve_first_then({}, {}).empty());
}

// A smooth convex object has no gap: nothing is carved first, and the
// result is plain constriction's. On the flat faces of a polyhedron the
// slivers under the long faces joining two flat faces are carved first,
// which keeps constriction from digging under those edges: the enclosed
// volume comes closer to the polyhedron's.
TEST(GapCarving, NothingOnSmoothConvexObjectsLessDiggingOnFlatFaces) {
  for (const int n : {500, 5000, 30000}) {
    const Eigen::MatrixX3d P = sim::sample_surface(sim::ellipsoid({3.0, 2.0, 1.0}, 5), n, static_cast<std::uint64_t>(n)).positions;
    const std::vector<int> depth = gap_depths(delaunay_complex(P));
    EXPECT_EQ(std::count(depth.begin(), depth.end(), -1), static_cast<std::ptrdiff_t>(depth.size())) << n << " points";
  }
  const TriangleMesh polyhedron = sim::ellipsoid({3.0, 2.0, 1.0}, 1);
  double volume = 0;
  for (Eigen::Index f = 0; f < polyhedron.faces.rows(); ++f) {
    const Eigen::Vector3d a = polyhedron.vertices.positions.row(polyhedron.faces(f, 0));
    const Eigen::Vector3d b = polyhedron.vertices.positions.row(polyhedron.faces(f, 1));
    const Eigen::Vector3d c = polyhedron.vertices.positions.row(polyhedron.faces(f, 2));
    volume += a.dot(b.cross(c)) / 6.0;
  }
  const Eigen::MatrixX3d P = sim::sample_surface(polyhedron, 30000, 30000).positions;
  ReconstructionOptions options = surface_defaults();
  const SurfaceReconstruction plain = reconstruct_surface(P, options);
  options.gaps = GapOptions{};
  const SurfaceReconstruction carved = reconstruct_surface(P, options);
  expect_valid_surface(carved, "flat-faced ellipsoid");
  EXPECT_TRUE(carved.statistics.all_on_boundary);
  EXPECT_GT(carved.statistics.gap_cells, 0u);
  std::printf("flat-faced ellipsoid: volume %.4f carved first, %.4f plain, true %.4f\n",
              carved.statistics.enclosed_measure, plain.statistics.enclosed_measure, volume);
  EXPECT_LT(std::abs(carved.statistics.enclosed_measure - volume), 0.8 * std::abs(plain.statistics.enclosed_measure - volume));
}

// Points on a sphere, about evenly spread (a Fibonacci spiral).
Eigen::MatrixX3d sphere(int n, const Eigen::Vector3d& centre) {
  Eigen::MatrixX3d P(n, 3);
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / n, r = std::sqrt(1.0 - z * z);
    P.row(i) = centre.transpose() + Eigen::RowVector3d(r * std::cos(golden * i), r * std::sin(golden * i), z);
  }
  return P;
}

// Two unit spheres 0.6 apart, sampled about 0.12 apart: the cells between
// them are carved first, none inside either.
TEST(GapCarving, CarvesBetweenTwoSpheresNotInside) {
  const int n = 900;
  Eigen::MatrixX3d P(2 * n, 3);
  P << sphere(n, Eigen::Vector3d(-1.3, 0, 0)), sphere(n, Eigen::Vector3d(1.3, 0, 0));
  const DelaunayComplex<3> dt = delaunay_complex(P);
  const std::vector<int> depth = gap_depths(dt);
  int between = 0;
  for (Eigen::Index c = 0; c < dt.cells.rows(); ++c) {
    if (depth[static_cast<std::size_t>(c)] < 0) continue;
    Eigen::RowVector3d centroid = Eigen::RowVector3d::Zero();
    for (int k = 0; k < 4; ++k) centroid += 0.25 * dt.points.row(dt.cells(c, k));
    EXPECT_GT((centroid - Eigen::RowVector3d(-1.3, 0, 0)).norm(), 0.95) << "cell " << c;
    EXPECT_GT((centroid - Eigen::RowVector3d(1.3, 0, 0)).norm(), 0.95) << "cell " << c;
    between += std::abs(centroid.x()) < 0.3;
  }
  EXPECT_GT(between, 100);

  ReconstructionOptions options = surface_defaults();
  options.gaps = GapOptions{};
  const SurfaceReconstruction carved = reconstruct_surface(P, options);
  expect_valid_surface(carved, "two spheres, gaps carved");
  EXPECT_TRUE(carved.statistics.all_on_boundary);
  EXPECT_EQ(carved.statistics.gap_cells, static_cast<std::size_t>(std::count_if(depth.begin(), depth.end(), [](int d) { return d >= 0; })));
}

// CGAL's diplodocus: its legs and tail stand close; without carving,
// constriction seals the gaps between them with webs. Web carving off on
// both sides: it takes many of those webs away afterwards (web_carving_test).
TEST(GapCarving, RecoversMoreOfARealMesh) {
  const TriangleMesh truth = io::read_mesh(test::cgal_data("meshes/diplodocus.off"));
  ReconstructionOptions options = surface_defaults();
  options.webs.reset();
  const SurfaceReconstruction plain = reconstruct_surface(truth.vertices.positions, options);
  options.gaps = GapOptions{};
  const SurfaceReconstruction carved = reconstruct_surface(truth.vertices.positions, options);
  expect_valid_surface(carved, "diplodocus");
  EXPECT_TRUE(carved.statistics.all_on_boundary);
  const double with = triangle_recall(truth.faces, carved.mesh.faces), without = triangle_recall(truth.faces, plain.mesh.faces);
  std::printf("diplodocus: recall %.3f with gap carving, %.3f without\n", with, without);
  EXPECT_GT(with, without + 0.01);
}

}  // namespace
}  // namespace scanstation
