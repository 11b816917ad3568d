#include "smoothing/patches_json.h"

#include "core/mesh_topology.h"
#include "smoothing/oscillation.h"
#include "smoothing/g1_verification.h"
#include "smoothing/reflection_lines.h"
#include "smoothing/sign_condition.h"
#include "smoothing/tessellation.h"
#include "smoothing/three_split.h"
#include "smoothing/vertex_normals.h"
#include "smoothing_test_meshes.h"

#include <nlohmann/json.hpp>

namespace scanstation {
namespace {

BezierSurface smooth(const TriangleMesh& mesh, bool least_squares_ratio) {
  Eigen::MatrixX3d N = vertex_normals(mesh.vertices.positions, mesh.faces);
  enforce_sign_condition(mesh.vertices.positions, mesh.faces, N);
  return three_split(mesh.vertices.positions, mesh.faces, N, mesh_edges(mesh.faces), {least_squares_ratio});
}

TEST(PatchesJson, ReadsBackToTheSameSurfaceBitForBit) {
  const TriangleMesh mesh = test::bumpy_sphere(8, 0.1);
  const BezierSurface surface = smooth(mesh, false);
  const nlohmann::json json = nlohmann::json::parse(patches_json(surface, "three-split"));
  ASSERT_EQ(json["patches"].size(), surface.patches.size());
  EXPECT_EQ(json["control_point_order"][4], "b111");
  for (std::size_t p = 0; p < surface.patches.size(); p += 7) {
    EXPECT_EQ(json["patches"][p]["macro"].get<int>(), surface.macro[p]);
    for (int i = 0; i < 10; ++i)
      for (int a = 0; a < 3; ++a)
        EXPECT_EQ(json["patches"][p]["control_points"][i][a].get<double>(), surface.patches[p][i][a]);
  }
}

TEST(ThreeSplitLeastSquaresRatio, StaysG1AndOscillatesLessOnRealMeshes) {
  for (const std::string& name : {std::string("elephant.off"), std::string("knot1.off")}) {
    const TriangleMesh mesh = test::real_mesh(name);
    const BezierSurface thesis = smooth(mesh, false), least_squares = smooth(mesh, true);
    EXPECT_LT(verify_g1(least_squares).max_normal_angle, 1e-8) << name;
    const Oscillation a = oscillation(thesis, mesh.vertices.positions, mesh.faces);
    const Oscillation b = oscillation(least_squares, mesh.vertices.positions, mesh.faces);
    EXPECT_LT(b.mean_relative, a.mean_relative) << name;
    EXPECT_LT(b.max_relative, a.max_relative) << name;
  }
}

TEST(Oscillation, IsZeroForAFlatPatchAndGrowsWithBulge) {
  BezierSurface surface;
  Eigen::MatrixX3d V(3, 3);
  V << 0, 0, 0, 3, 0, 0, 0, 3, 0;
  Eigen::MatrixX3i F(1, 3);
  F << 0, 1, 2;
  CubicTriangle flat;
  for (int i = 0; i <= 3; ++i)
    for (int j = 0; i + j <= 3; ++j) flat[control_index(i, j, 3 - i - j)] = Eigen::Vector3d(j, 3 - i - j, 0.0);
  surface.patches = {flat};
  surface.macro = {0};
  EXPECT_NEAR(oscillation(surface, V, F).max_relative, 0.0, 1e-15);
  surface.patches[0][control_index(1, 1, 1)].z() = 1.0;
  const double edge = (3.0 + 3.0 + std::sqrt(18.0)) / 3.0;
  EXPECT_NEAR(oscillation(surface, V, F, 3).max_relative, 6.0 / 27.0 / edge, 1e-12);  // P(1/3,1/3,1/3).z = 6/27
}

TEST(ReflectionLines, RendersAPng) {
  const TriangleMesh mesh = sim::icosphere(2);
  const std::string png = reflection_lines_png(tessellate(smooth(test::bumpy_sphere(1, 0.05), false), 3), mesh,
                                               {64, 48, 6.0});
  EXPECT_EQ(png.substr(1, 3), "PNG");
}

}  // namespace
}  // namespace scanstation

namespace scanstation {
namespace {

TEST(Tessellation, StreamedPlyHasTheSameWatertightMesh) {
  const BezierSurface surface = smooth(test::bumpy_sphere(6, 0.1), false);
  test::ScratchFolder dir;
  for (const int density : {1, 2, 5}) {
    std::string name = "t";  // appended piecewise: GCC 12 misreports a chained '+' here (-Wrestrict)
    name.append(std::to_string(density)).append(".ply");
    const std::filesystem::path path = dir / name;
    write_tessellation_ply(surface, density, path, io::Overwrite::refuse);
    const TriangleMesh streamed = io::read_mesh(path);
    const TriangleMesh in_memory = tessellate(surface, density);
    ASSERT_EQ(streamed.vertex_count(), in_memory.vertex_count()) << density;
    ASSERT_EQ(streamed.face_count(), in_memory.face_count()) << density;
    const MeshTopology topology = mesh_topology(streamed);
    EXPECT_TRUE(topology.closed && topology.oriented) << density;
    EXPECT_EQ(topology.genus.value_or(-1), 0) << density;
    // Same points (in another order) and unit normals.
    const auto sorted = [](const Eigen::MatrixX3d& X) {
      std::vector<std::array<double, 3>> rows(X.rows());
      for (Eigen::Index i = 0; i < X.rows(); ++i) rows[i] = {X(i, 0), X(i, 1), X(i, 2)};
      std::sort(rows.begin(), rows.end());
      return rows;
    };
    EXPECT_EQ(sorted(streamed.vertices.positions), sorted(in_memory.vertices.positions)) << density;
    EXPECT_NEAR(streamed.vertices.normals.rowwise().norm().minCoeff(), 1.0, 1e-12);
  }
}

}  // namespace
}  // namespace scanstation
