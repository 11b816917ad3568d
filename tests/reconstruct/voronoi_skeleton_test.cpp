// Shortest Voronoi skeleton (thesis §4.3.4), the comparison baseline of §5.6.
#include "core/errors.h"
#include "core/polygon.h"
#include "reconstruct/boundary_reconstruction.h"
#include "reconstruct/delaunay_complex.h"
#include "reconstruct/voronoi_skeleton.h"
#include "sim/outlines.h"
#include "sim/random.h"
#include "sim/shapes.h"
#include "test_support.h"
#include "valid_surface.h"

#include <Eigen/LU>
#include <limits>

namespace scanstation {
namespace {

// Reference: the same trial-and-error growth written the slow obvious way —
// from every seed, repeatedly scan all tree cells for the shortest Voronoi
// edge to a cell that brings a new point — and the shortest complete tree.
template <int D>
std::pair<double, std::vector<char>> reference_skeleton(const DelaunayComplex<D>& dt) {
  const Eigen::Index cells = dt.cells.rows(), points = dt.points.rows();
  std::vector<Eigen::Matrix<double, D, 1>> centre(static_cast<std::size_t>(cells));
  for (Eigen::Index c = 0; c < cells; ++c) {
    Eigen::Matrix<double, D + 1, D + 1> A;
    Eigen::Matrix<double, D + 1, 1> b;
    for (int k = 0; k <= D; ++k) {  // |x|² − 2 p·x + (|p|² − r²) = 0 for each vertex p
      const Eigen::Matrix<double, D, 1> p = dt.points.row(dt.cells(c, k)).transpose();
      A.row(k) << 2.0 * p.transpose(), 1.0;
      b(k) = p.squaredNorm();
    }
    centre[static_cast<std::size_t>(c)] = A.fullPivLu().solve(b).template head<D>();
  }
  double best = std::numeric_limits<double>::infinity();
  std::vector<char> best_tree;
  for (Eigen::Index seed = 0; seed < cells; ++seed) {
    std::vector<char> tree(static_cast<std::size_t>(cells), 0), on(static_cast<std::size_t>(points), 0);
    const auto add = [&](Eigen::Index c) {
      tree[static_cast<std::size_t>(c)] = 1;
      for (int k = 0; k <= D; ++k) on[static_cast<std::size_t>(dt.cells(c, k))] = 1;
    };
    add(seed);
    double length = 0.0;
    for (;;) {
      double shortest = std::numeric_limits<double>::infinity();
      Eigen::Index next = -1;
      for (Eigen::Index c = 0; c < cells; ++c) {
        if (!tree[static_cast<std::size_t>(c)]) continue;
        for (int i = 0; i <= D; ++i) {
          const int n = dt.neighbors(c, i);
          if (n < 0 || tree[static_cast<std::size_t>(n)]) continue;
          int apex = -1;
          for (int j = 0; j <= D; ++j)
            if (dt.neighbors(n, j) == c) apex = dt.cells(n, j);
          if (on[static_cast<std::size_t>(apex)]) continue;
          const double d = (centre[static_cast<std::size_t>(c)] - centre[static_cast<std::size_t>(n)]).norm();
          if (d < shortest) shortest = d, next = n;
        }
      }
      if (next < 0) break;
      length += shortest;
      add(next);
    }
    if (std::count(on.begin(), on.end(), 1) == points && length < best) best = length, best_tree = tree;
  }
  return {best, best_tree};
}

TEST(VoronoiSkeleton2, EqualsTheObviousTrialAndErrorSearch) {
  sim::Random random(21);
  int complete = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const Eigen::Index n = 4 + static_cast<Eigen::Index>(random.below(30));
    Eigen::MatrixX2d P(n, 2);
    for (Eigen::Index i = 0; i < n; ++i) P.row(i) << random.uniform(), random.uniform();
    const DelaunayComplex<2> dt = delaunay_complex(P);
    const auto [length, tree] = reference_skeleton(dt);
    const Constriction<2> skeleton = voronoi_skeleton(dt);
    if (tree.empty()) {
      EXPECT_FALSE(skeleton.all_on_boundary) << trial;
      continue;
    }
    ++complete;
    EXPECT_TRUE(skeleton.all_on_boundary) << trial;
    EXPECT_EQ(skeleton.kept, tree) << trial;
    // A dual tree through every point: N − 2 triangles, an N-gon.
    EXPECT_EQ(std::count(skeleton.kept.begin(), skeleton.kept.end(), 1), n - 2) << trial;
    EXPECT_EQ(skeleton.boundary.rows(), n) << trial;
  }
  EXPECT_GT(complete, 30);
}

TEST(VoronoiSkeleton3, EqualsTheObviousTrialAndErrorSearch) {
  sim::Random random(22);
  int complete = 0;
  for (int trial = 0; trial < 12; ++trial) {
    const Eigen::Index n = 5 + static_cast<Eigen::Index>(random.below(20));
    Eigen::MatrixX3d P(n, 3);
    for (Eigen::Index i = 0; i < n; ++i) P.row(i) << random.uniform(), random.uniform(), random.uniform();
    const DelaunayComplex<3> dt = delaunay_complex(P);
    const auto [length, tree] = reference_skeleton(dt);
    const Constriction<3> skeleton = voronoi_skeleton(dt);
    EXPECT_EQ(skeleton.all_on_boundary, !tree.empty()) << trial;
    if (!tree.empty()) {
      EXPECT_EQ(skeleton.kept, tree) << trial;
      ++complete;
    }
  }
  EXPECT_GT(complete, 6);
}

TEST(VoronoiSkeleton2, FindsTheOutlineOfAnObjectWithAClearSkeleton) {
  // The chalice's stem and bowl are a clear skeleton (the case §4.3.4 is
  // made for): the skeleton tree is the outline's own triangulation.
  const Polygon2 chalice = sim::chalice_outline(200);
  ReconstructionOptions skeleton;
  skeleton.voronoi_skeleton = VoronoiSkeletonOptions{};
  const CurveReconstruction r = reconstruct_curve(chalice.vertices, skeleton);
  EXPECT_TRUE(r.statistics.all_on_boundary);
  EXPECT_TRUE(is_simple(r.polygon));
  EXPECT_NEAR(twice_signed_area(r.polygon), twice_signed_area(chalice), 1e-9);
  // Fewer seeds than cells: still a simple polygon through every point.
  skeleton.voronoi_skeleton->max_seeds = 7;
  const CurveReconstruction few = reconstruct_curve(chalice.vertices, skeleton);
  EXPECT_TRUE(is_simple(few.polygon));
  EXPECT_EQ(few.polygon.size() + static_cast<Eigen::Index>(few.statistics.interior_vertices.size()), chalice.size());
}

TEST(VoronoiSkeleton3, GivesValidBoundariesOnSmallShapes) {
  const std::vector<std::pair<std::string, TriangleMesh>> shapes = {
      {"icosphere", sim::icosphere(2)},
      {"ellipsoid", sim::ellipsoid({2.0, 1.0, 0.5}, 2)},
  };
  for (const auto& [name, shape] : shapes) {
    ReconstructionOptions skeleton;
    skeleton.voronoi_skeleton = VoronoiSkeletonOptions{};
    const SurfaceReconstruction r = reconstruct_surface(shape.vertices.positions, skeleton);
    expect_valid_surface(r, name);
  }
  ReconstructionOptions keep;
  keep.voronoi_skeleton = VoronoiSkeletonOptions{};
  keep.constriction.keep = Eigen::MatrixXi::Zero(1, 3);
  test::expect_error<InvalidInput>([&] { reconstruct_surface(sim::icosphere(1).vertices.positions, keep); },
                                   {"Voronoi skeleton"});
}

}  // namespace
}  // namespace scanstation
