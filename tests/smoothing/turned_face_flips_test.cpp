#include "smoothing/turned_face_flips.h"

#include "core/mesh_topology.h"
#include "sim/random.h"
#include "smoothing/sign_condition.h"
#include "smoothing/surface_smoothing.h"
#include "smoothing/vertex_normals.h"
#include "smoothing_test_meshes.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <map>
#include <set>

namespace scanstation {
namespace {

bool faces_its_corners(const Eigen::MatrixX3d& V, const Eigen::MatrixX3d& N, const Eigen::MatrixX3i& F,
                       Eigen::Index f) {
  const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
  const Eigen::Vector3d n = (b - a).cross(c - a);
  for (int k = 0; k < 3; ++k)
    if (!(n.dot(Eigen::Vector3d(N.row(F(f, k)))) > 0.0)) return false;
  return true;
}

std::size_t turned_faces(const Eigen::MatrixX3d& V, const Eigen::MatrixX3d& N, const Eigen::MatrixX3i& F) {
  std::size_t turned = 0;
  for (Eigen::Index f = 0; f < F.rows(); ++f) turned += !faces_its_corners(V, N, F, f);
  return turned;
}

// A bumpy sphere whose vertex c of some faces (c, a, b) is moved a little
// beyond the middle of the edge a–b: a sliver facing inwards, as a scan
// leaves between two laser profiles.
struct SliveredSphere {
  TriangleMesh mesh;
  std::size_t slivers = 0;
};

SliveredSphere slivered_sphere(std::uint64_t seed, int wanted) {
  SliveredSphere s{test::bumpy_sphere(seed, 0.05)};
  auto& V = s.mesh.vertices.positions;
  const Eigen::MatrixX3i& F = s.mesh.faces;
  sim::Random random(seed + 100);
  std::set<int> moved;  // a moved vertex and its neighbours stay as they are
  for (int attempt = 0; attempt < 200 && static_cast<int>(s.slivers) < wanted; ++attempt) {
    const auto f = static_cast<Eigen::Index>(random.uniform() * static_cast<double>(F.rows())) % F.rows();
    const int k = static_cast<int>(random.uniform() * 3.0) % 3;
    const int c = F(f, k), a = F(f, (k + 1) % 3), b = F(f, (k + 2) % 3);
    if (moved.count(c) || moved.count(a) || moved.count(b)) continue;
    const Eigen::Vector3d middle = (V.row(a) + V.row(b)) / 2.0;
    const Eigen::Vector3d inward = middle - Eigen::Vector3d(V.row(c));
    V.row(c) = middle + 0.02 * inward;  // just across the edge, in the face's plane
    moved.insert({c, a, b});
    ++s.slivers;
  }
  return s;
}

TEST(TurnedFaceFlips, TurnsEverySliverBackAndKeepsAClosedManifold) {
  for (std::uint64_t seed = 1; seed <= 12; ++seed) {
    const SliveredSphere s = slivered_sphere(seed, 6);
    const auto& V = s.mesh.vertices.positions;
    Eigen::MatrixX3i F = s.mesh.faces;
    const Eigen::MatrixX3d N = vertex_normals(V, F);
    const std::size_t before = turned_faces(V, N, F);
    ASSERT_GE(before, s.slivers) << seed;
    EXPECT_FALSE(sign_condition_violations(V, F, N).empty()) << seed;

    const std::vector<int> changed = flip_turned_faces(V, F, N);
    EXPECT_TRUE(std::is_sorted(changed.begin(), changed.end()));
    EXPECT_EQ(turned_faces(V, N, F), 0u) << seed;
    for (const int f : changed) EXPECT_TRUE(faces_its_corners(V, N, F, f)) << seed << " face " << f;
    // The faces not reported are the mesh's own, bit for bit.
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
      if (!std::binary_search(changed.begin(), changed.end(), static_cast<int>(f))) {
        EXPECT_EQ(F.row(f), s.mesh.faces.row(f)) << seed;
      }
    }
    TriangleMesh flipped = s.mesh;
    flipped.faces = F;
    const MeshTopology topology = mesh_topology(flipped);
    EXPECT_TRUE(topology.closed && topology.manifold && topology.oriented) << seed;
    EXPECT_EQ(topology.genus.value_or(-1), 0) << seed;
    EXPECT_EQ(topology.isolated_vertices, 0u) << seed;
  }
}

// Nothing to flip on a mesh whose faces all face their corners' normals:
// the mesh is returned as it was.
TEST(TurnedFaceFlips, LeavesAGoodMeshAlone) {
  for (const TriangleMesh& mesh : {test::bumpy_sphere(1, 0.1), test::real_mesh("eight.off")}) {
    Eigen::MatrixX3i F = mesh.faces;
    const Eigen::MatrixX3d N = vertex_normals(mesh.vertices.positions, F);
    ASSERT_EQ(turned_faces(mesh.vertices.positions, N, F), 0u);
    EXPECT_TRUE(flip_turned_faces(mesh.vertices.positions, F, N).empty());
    EXPECT_EQ(F, mesh.faces);
  }
}

// Through smooth_surface: the sign condition holds after the flips where it
// could not before, the report's faces are the flipped ones, and the
// surface still passes through every vertex with no fold.
TEST(TurnedFaceFlips, LetTheSmoothSurfaceMeetTheSignCondition) {
  const SliveredSphere s = slivered_sphere(3, 6);
  SurfaceSmoothingOptions plain;
  const SurfaceSmoothing before = smooth_surface(s.mesh, plain);
  EXPECT_GT(before.sign_condition_violations, 0u);
  EXPECT_TRUE(before.flipped_faces.empty());
  EXPECT_EQ(before.faces, s.mesh.faces);
  SurfaceSmoothingOptions flipping;
  flipping.flip_turned_faces = true;
  const SurfaceSmoothing after = smooth_surface(s.mesh, flipping);
  EXPECT_FALSE(after.flipped_faces.empty());
  EXPECT_EQ(after.sign_condition_violations, 0u);
  EXPECT_EQ(after.g1.folded_edges, 0u);
  EXPECT_LT(after.g1.max_normal_angle_exact, 1e-8);
  EXPECT_EQ(after.surface.patches.size(), 6u * static_cast<std::size_t>(s.mesh.face_count()));
  const nlohmann::json report = smoothing_report(after, flipping, s.mesh.face_count());
  ASSERT_EQ(report["flipped_faces"].size(), after.flipped_faces.size());
  const auto& first = report["flipped_faces"][0];
  EXPECT_EQ(first[0], after.flipped_faces[0]);
  EXPECT_EQ(first[1], after.faces(after.flipped_faces[0], 0));
}

}  // namespace
}  // namespace scanstation
