#include "smoothing/tessellation.h"

#include "core/errors.h"
#include "core/mesh_topology.h"
#include "sim/random.h"
#include "sim/shapes.h"
#include "smoothing/six_split.h"
#include "smoothing/tessellation_density.h"
#include "smoothing_test_meshes.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

namespace scanstation {
namespace {


// One patch over the unit right triangle in z = 0 with b111 lifted to z = 1:
// P = (u, v, w)·corners + 6uvw e_z, zero on the edges.
BezierSurface bump() {
  const std::array<Eigen::Vector3d, 3> corner = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0),
                                                 Eigen::Vector3d(0, 1, 0)};
  CubicTriangle patch;
  for (int i = 0; i <= 3; ++i)
    for (int k = 0; i + k <= 3; ++k) {
      const int j = 3 - i - k;
      patch[static_cast<std::size_t>(control_index(i, j, k))] = (i * corner[0] + j * corner[1] + k * corner[2]) / 3.0;
    }
  patch[static_cast<std::size_t>(control_index(1, 1, 1))].z() = 1.0;
  BezierSurface surface;
  surface.patches.push_back(patch);
  surface.macro.push_back(0);
  return surface;
}

std::vector<std::array<double, 3>> sorted_rows(const Eigen::MatrixX3d& X) {
  std::vector<std::array<double, 3>> rows(static_cast<std::size_t>(X.rows()));
  for (Eigen::Index i = 0; i < X.rows(); ++i) rows[static_cast<std::size_t>(i)] = {X(i, 0), X(i, 1), X(i, 2)};
  std::sort(rows.begin(), rows.end());
  return rows;
}

// Closed, oriented (a band zipped the wrong way round would break the
// pairing of its edges), genus 0, the plan's face count.
void expect_watertight(const TriangleMesh& mesh, std::size_t faces) {
  ASSERT_EQ(static_cast<std::size_t>(mesh.face_count()), faces);
  const MeshTopology topology = mesh_topology(mesh);
  EXPECT_TRUE(topology.closed && topology.oriented);
  EXPECT_EQ(topology.genus.value_or(-1), 0);
  EXPECT_EQ(topology.degenerate_faces, 0u);
}

// A closed polyhedron as flat patches (the control points on each
// triangle): a tessellation triangle then lies in its patch's plane, and it
// turns as the patch exactly when it is counter-clockwise in the domain.
BezierSurface flat_patches(const TriangleMesh& mesh) {
  BezierSurface surface;
  for (Eigen::Index f = 0; f < mesh.face_count(); ++f) {
    CubicTriangle patch;
    for (int i = 0; i <= 3; ++i)
      for (int k = 0; i + k <= 3; ++k) {
        const int j = 3 - i - k;
        patch[static_cast<std::size_t>(control_index(i, j, k))] =
            (i * mesh.vertices.positions.row(mesh.faces(f, 0)) + j * mesh.vertices.positions.row(mesh.faces(f, 1)) +
             k * mesh.vertices.positions.row(mesh.faces(f, 2)))
                .transpose() /
            3.0;
      }
    surface.patches.push_back(patch);
    surface.macro.push_back(static_cast<int>(f));
  }
  return surface;
}

TEST(Tessellation, DeviationOfABumpAtKnownValues) {
  const BezierSurface surface = bump();
  // Densities 1 and 2 both leave a triangle around (1/3, 1/3, 1/3) whose
  // corners lie on the patch edges: the bump's full height 6/27 there.
  EXPECT_NEAR(tessellation_deviation(surface, 1), 6.0 / 27.0, 1e-15);
  EXPECT_NEAR(tessellation_deviation(surface, 2), 6.0 / 27.0, 1e-15);
  // Density 3 has a point at the centre: what is left is the bump over the
  // triangles around it, at most 6·(4/9)(1/9)(4/9)-ish — half or less.
  EXPECT_LT(tessellation_deviation(surface, 3), 0.12);
  // Then it shrinks as 1/n²: a chordal error.
  EXPECT_NEAR(tessellation_deviation(surface, 8) / tessellation_deviation(surface, 16), 4.0, 0.5);
  const ChosenTessellation chosen = adaptive_tessellation(surface, 0.05, 16);
  EXPECT_LE(chosen.deviation, 0.05);
  EXPECT_GT(tessellation_deviation(surface, chosen.largest_density - 1), 0.05);  // the smallest within 0.05
  EXPECT_EQ(chosen.above, 0u);
  EXPECT_EQ(adaptive_tessellation(surface, 1e-9, 5).above, 1u);  // the limit reached
  BezierSurface flat = surface;
  flat.patches[0][static_cast<std::size_t>(control_index(1, 1, 1))].z() = 0.0;
  EXPECT_EQ(tessellation_deviation(flat, 1), 0.0);
}

TEST(Tessellation, MixedDensitiesStayWatertightStreamedOrNot) {
  const BezierSurface surface = test::six_split_surface(test::bumpy_sphere(3, 0.1));
  sim::Random random(11);
  test::ScratchFolder dir;
  for (int round = 0; round < 3; ++round) {
    // Every combination of a patch's density and its edges' up to 7,
    // including the fans of densities 1 and 2 beside finer neighbours.
    std::vector<int> density(surface.patches.size());
    for (int& n : density) n = 1 + static_cast<int>(random.uniform() * (round == 0 ? 2 : 7));
    const TessellationPlan plan = plan_from_densities(surface, density);
    const TriangleMesh in_memory = tessellate(surface, plan);
    expect_watertight(in_memory, plan.face_count());
    const std::filesystem::path path = dir / ("mixed" + std::to_string(round) + ".ply");
    write_tessellation_ply(surface, plan, path, io::Overwrite::refuse);
    // The plan carries the shared patch edges; found again, they give the same file.
    EXPECT_EQ(plan.shared.size(), patch_adjacency(surface).pairs.size());
    TessellationPlan bare = plan;
    bare.shared.clear();
    const std::filesystem::path again = dir / ("again" + std::to_string(round) + ".ply");
    write_tessellation_ply(surface, bare, again, io::Overwrite::refuse);
    const auto bytes = [](const std::filesystem::path& file) {
      std::ifstream in(file, std::ios::binary);
      return std::string(std::istreambuf_iterator<char>(in), {});
    };
    EXPECT_EQ(bytes(path), bytes(again));
    if (round == 0) {
      TessellationPlan wrong = plan;
      wrong.shared.push_back({0, 0, static_cast<int>(surface.patches.size()), 1});
      EXPECT_THROW(write_tessellation_ply(surface, wrong, dir / "wrong.ply", io::Overwrite::refuse), InvalidInput);
      wrong.shared.back() = {0, 0, 1, 3};  // patches that exist, an edge that does not
      EXPECT_THROW(write_tessellation_ply(surface, wrong, dir / "wrong.ply", io::Overwrite::refuse), InvalidInput);
    }
    const TriangleMesh streamed = io::read_mesh(path);
    ASSERT_EQ(streamed.vertex_count(), in_memory.vertex_count());
    expect_watertight(streamed, plan.face_count());
    EXPECT_EQ(sorted_rows(streamed.vertices.positions), sorted_rows(in_memory.vertices.positions));
  }
}

TEST(Tessellation, EveryTriangleOfMixedDensitiesTurnsAsItsPatch) {
  const TriangleMesh mesh = sim::icosphere(1);
  const BezierSurface surface = flat_patches(mesh);
  sim::Random random(5);
  for (int round = 0; round < 4; ++round) {
    std::vector<int> density(surface.patches.size());
    for (int& n : density) n = 1 + static_cast<int>(random.uniform() * 9);
    const TessellationPlan plan = plan_from_densities(surface, density);
    const TriangleMesh dense = tessellate(surface, plan);
    expect_watertight(dense, plan.face_count());
    const auto& X = dense.vertices.positions;
    std::size_t turned = 0;
    for (Eigen::Index f = 0; f < dense.face_count(); ++f) {
      const Eigen::Vector3d a = X.row(dense.faces(f, 0)), b = X.row(dense.faces(f, 1)), c = X.row(dense.faces(f, 2));
      // The face's own normal against the normal the patch gives its corners.
      const Eigen::Vector3d n = (b - a).cross(c - a);
      const Eigen::Vector3d patch_normal = dense.vertices.normals.row(dense.faces(f, 0));
      turned += n.dot(patch_normal) > 1e-12 * n.norm();
    }
    EXPECT_EQ(turned, static_cast<std::size_t>(dense.face_count())) << round;
  }
}

TEST(Tessellation, AdaptivePatchesTakeTheSmallestDensityWithinTheTolerance) {
  const BezierSurface surface = test::six_split_surface(test::bumpy_sphere(5, 0.15));
  const double tolerance = 5e-3;  // of a unit sphere whose six-split bulges up to 0.1 over a patch
  const ChosenTessellation chosen = adaptive_tessellation(surface, tolerance, 12);
  std::array<std::size_t, 13> at{};
  std::size_t above = 0;
  double largest = 0;
  for (std::size_t p = 0; p < surface.patches.size(); ++p) {
    const int n = chosen.plan.inner[p];
    ++at[static_cast<std::size_t>(n)];
    BezierSurface one;
    one.patches.push_back(surface.patches[p]);
    const double deviation = tessellation_deviation(one, n);
    largest = std::max(largest, deviation);
    if (n < 12) {
      EXPECT_LE(deviation, tolerance) << p;
    }
    above += deviation > tolerance;
    if (n > 1) {
      EXPECT_GT(tessellation_deviation(one, n - 1), tolerance) << p;
    }
    for (int k = 0; k < 3; ++k) EXPECT_GE(chosen.plan.edge[3 * p + static_cast<std::size_t>(k)], n);
  }
  EXPECT_EQ(chosen.above, above);
  EXPECT_EQ(chosen.deviation, largest);
  EXPECT_LT(above, surface.patches.size() / 20);
  // Mixed: the point of choosing per patch.
  EXPECT_GT(std::count_if(at.begin(), at.end(), [](std::size_t c) { return c > 0; }), 1);
  EXPECT_LT(chosen.plan.face_count(), uniform_plan(surface, chosen.largest_density).face_count());
  expect_watertight(tessellate(surface, chosen.plan), chosen.plan.face_count());
}

// A surface scaled by a power of two is tessellated as the surface itself:
// the same densities, the same unit normals bit for bit, the positions, the
// deviation and the default tolerance scaled exactly. Near 1e±160 the
// squares of lengths leave the double range: the tolerance came out
// infinite (and `smooth` refused), the deviations 0 (every patch at
// density 1) and the normals zero.
TEST(Tessellation, ScaledByAPowerOfTwoTheSameTessellation) {
  const BezierSurface surface = test::six_split_surface(test::bumpy_sphere(4, 0.15));
  const ChosenTessellation chosen = choose_tessellation(surface, std::nullopt);
  const TriangleMesh mesh = tessellate(surface, chosen.plan);
  ASSERT_GT(chosen.largest_density, 1);
  for (const double scale : {0x1p-1000, 0x1p-540, 0x1p-110, 0x1p110, 0x1p540, 0x1p1000}) {
    BezierSurface scaled = surface;
    for (CubicTriangle& patch : scaled.patches)
      for (Eigen::Vector3d& b : patch) b *= scale;
    EXPECT_EQ(default_tessellation_tolerance(scaled), default_tessellation_tolerance(surface) * scale) << scale;
    const ChosenTessellation again = choose_tessellation(scaled, std::nullopt);
    EXPECT_EQ(again.plan.inner, chosen.plan.inner) << scale;
    EXPECT_EQ(again.plan.edge, chosen.plan.edge) << scale;
    EXPECT_EQ(again.deviation, chosen.deviation * scale) << scale;
    const TriangleMesh dense = tessellate(scaled, again.plan);
    EXPECT_EQ(dense.faces, mesh.faces) << scale;
    EXPECT_EQ(dense.vertices.normals, mesh.vertices.normals) << scale;
    EXPECT_EQ(Eigen::MatrixX3d(dense.vertices.positions / scale), mesh.vertices.positions) << scale;
  }
}

TEST(Tessellation, UniformPlanIsTheRegularGrid) {
  const BezierSurface surface = test::six_split_surface(test::bumpy_sphere(2, 0.1));
  for (const int n : {1, 2, 3, 5}) {
    const TriangleMesh mesh = tessellate(surface, n);
    EXPECT_EQ(static_cast<std::size_t>(mesh.face_count()), surface.patches.size() * static_cast<std::size_t>(n * n));
    // Euler: V − E + F = 2 with E = 3F/2.
    EXPECT_EQ(mesh.vertex_count(), 2 + mesh.face_count() / 2);
  }
  EXPECT_THROW(uniform_plan(surface, 0), InvalidInput);
  std::vector<int> density(surface.patches.size(), 2);
  TessellationPlan plan = plan_from_densities(surface, density);
  plan.edge[0] = 1;  // fewer segments than its patch
  EXPECT_THROW(tessellate(surface, plan), InvalidInput);
}

}  // namespace
}  // namespace scanstation
