// Folds re-triangulated flat (reconstruct/unfold_boundary.h): the surface
// stays closed, 2-manifold, oriented, genus 0, simple and through the same
// points, and has fewer folds.
#include "core/io/mesh_io.h"
#include "core/mesh_topology.h"
#include "core/self_intersections.h"
#include "reconstruct/boundary_reconstruction.h"
#include "reconstruct/unfold_boundary.h"
#include "sim/random.h"
#include "test_support.h"
#include "valid_surface.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <set>
#include <string>

namespace scanstation {
namespace {

void expect_same_points_and_valid(const TriangleMesh& before, const TriangleMesh& after, const std::string& what) {
  EXPECT_EQ(after.faces.rows(), before.faces.rows()) << what;  // a disk replaced by a disk on the same vertices
  const MeshTopology t = mesh_topology(after);
  EXPECT_TRUE(t.closed) << what;
  EXPECT_TRUE(t.manifold) << what;
  EXPECT_TRUE(t.oriented) << what;
  EXPECT_EQ(t.genus, 0) << what;
  EXPECT_EQ(t.components, 1u) << what;
  EXPECT_EQ(t.isolated_vertices, mesh_topology(before).isolated_vertices) << what;
  EXPECT_EQ(self_intersections(after), std::optional<std::size_t>(0)) << what << ": not simple";
}

std::set<std::array<int, 3>> face_set(const Eigen::MatrixX3i& F) {
  std::set<std::array<int, 3>> out;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    std::array<int, 3> t{F(f, 0), F(f, 1), F(f, 2)};
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    out.insert(t);
  }
  return out;
}

// The demo's live boundary of a scanned ellipsoid, before unfolding: its flat
// top (z ≈ 51.9, no point within 1.8 of the axis) was bridged by thin
// triangles folded over each other (6 edges turning by more than 170°).
TEST(UnfoldBoundary, UndoesTheFoldsOfAScannedFlatTopAndNothingElse) {
  const TriangleMesh before =
      io::read_mesh(std::filesystem::path(SCANSTATION_SOURCE_DIR) / "tests/reconstruct/data/folded_scan.ply");
  TriangleMesh after = before;
  const UnfoldStatistics s = unfold_boundary(after.vertices.positions, after.faces);
  EXPECT_EQ(s.folds_before, 6u);
  EXPECT_EQ(s.folds_after, 0u);
  EXPECT_GE(s.retriangulated, 1u);
  expect_same_points_and_valid(before, after, "scanned ellipsoid");
  const auto old_faces = face_set(before.faces);
  std::size_t changed = 0;
  for (const auto& t : face_set(after.faces))
    if (!old_faces.count(t)) {
      ++changed;
      for (const int v : t) EXPECT_GT(after.vertices.positions(v, 2), 51.0) << "a face away from the top changed";
    }
  EXPECT_GT(changed, 0u);
  EXPECT_LT(changed, 40u);
}

// A surface with a hole at its fold (not closed, against the precondition)
// is handled without harm: the open patch stays as it is.
TEST(UnfoldBoundary, LeavesAnOpenPatchAlone) {
  const TriangleMesh closed =
      io::read_mesh(std::filesystem::path(SCANSTATION_SOURCE_DIR) / "tests/reconstruct/data/folded_scan.ply");
  // Face 17 is the thin triangle lying over the others: all its edges fold.
  const Eigen::Index lid = 17;
  ASSERT_EQ(closed.faces.row(lid), Eigen::RowVector3i(987, 2077, 2149));
  Eigen::MatrixX3i F(closed.faces.rows() - 1, 3);
  Eigen::Index kept = 0;
  for (Eigen::Index f = 0; f < closed.faces.rows(); ++f)
    if (f != lid) F.row(kept++) = closed.faces.row(f);
  const Eigen::MatrixX3i before = F;
  const UnfoldStatistics s = unfold_boundary(closed.vertices.positions, F);
  EXPECT_GT(s.folds_before, 0u);  // the folds around the hole are still there
  EXPECT_EQ(s.retriangulated, 0u);
  EXPECT_EQ(F, before);
}

// Real meshes, reconstructed without unfolding, then unfolded on their own
// (each has patches to unfold with the defaults; hand has none since the
// γ-guide's c1 went from 0.7 to 0.5).
TEST(UnfoldBoundary, KeepsRealReconstructionsValidWithFewerFolds) {
  for (const std::string name : {"bull", "cow", "dino"}) {
    ReconstructionOptions options = surface_defaults();
    options.unfold = false;
    const SurfaceReconstruction r =
        reconstruct_surface(io::read_mesh(test::cgal_data("meshes/" + name + ".off")).vertices.positions, options);
    TriangleMesh after = r.mesh;
    const UnfoldStatistics s = unfold_boundary(after.vertices.positions, after.faces);
    EXPECT_GT(s.folds_before, 0u) << name;
    EXPECT_LT(s.folds_after, s.folds_before) << name;
    EXPECT_GT(s.retriangulated, 0u) << name;
    expect_same_points_and_valid(r.mesh, after, name);
    // The folds left, counted afresh, are those reported.
    Eigen::MatrixX3i again = after.faces;
    EXPECT_EQ(unfold_boundary(after.vertices.positions, again).folds_before, s.folds_after) << name;
  }
}

// Faces that must stay (§5.7) stay: those unfolding would replace are kept.
TEST(UnfoldBoundary, KeepsTheFacesAskedToStay) {
  ReconstructionOptions options = surface_defaults();
  options.unfold = false;
  const SurfaceReconstruction r =
      reconstruct_surface(io::read_mesh(test::cgal_data("meshes/bull.off")).vertices.positions, options);
  Eigen::MatrixX3i free = r.mesh.faces;
  unfold_boundary(r.mesh.vertices.positions, free);
  const auto after = face_set(free);
  std::vector<std::array<int, 3>> replaced;
  for (const auto& t : face_set(r.mesh.faces))
    if (!after.count(t)) replaced.push_back(t);
  ASSERT_GT(replaced.size(), 0u);
  Eigen::MatrixXi keep(static_cast<Eigen::Index>(replaced.size()), 3);
  for (std::size_t k = 0; k < replaced.size(); ++k)
    keep.row(static_cast<Eigen::Index>(k)) << replaced[k][0], replaced[k][1], replaced[k][2];
  Eigen::MatrixX3i kept = r.mesh.faces;
  unfold_boundary(r.mesh.vertices.positions, kept, keep);
  const auto present = face_set(kept);
  for (const auto& t : replaced) EXPECT_TRUE(present.count(t)) << t[0] << " " << t[1] << " " << t[2];
}

// Nearly coplanar points are where folds come from: thin random slabs, with
// unfolding in the pipeline (the default). Every result stays valid.
TEST(UnfoldBoundary, ReconstructionsOfThinSlabsStayValid) {
  std::size_t folds = 0, left = 0;
  for (int seed = 1; seed <= 12; ++seed) {
    sim::Random random(static_cast<std::uint64_t>(seed));
    Eigen::MatrixX3d P(300, 3);
    for (Eigen::Index i = 0; i < P.rows(); ++i)
      P.row(i) << random.uniform(), random.uniform(), (random.uniform() < 0.5 ? 0.0 : 0.01) + 1e-4 * random.normal();
    const SurfaceReconstruction r = reconstruct_surface(P);
    expect_valid_surface(r, "slab " + std::to_string(seed));
    EXPECT_TRUE(r.statistics.all_on_boundary) << seed;
    EXPECT_LE(r.statistics.folds_left, r.statistics.folds) << seed;
    folds += r.statistics.folds;
    left += r.statistics.folds_left;
  }
  EXPECT_GT(folds, 0u);  // the inputs do fold
  EXPECT_LT(left, folds);
}

// Without folds nothing changes, bit for bit.
TEST(UnfoldBoundary, LeavesASurfaceWithoutFoldsAlone) {
  sim::Random random(3);
  Eigen::MatrixX3d P(2000, 3);
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    const Eigen::Vector3d p(random.normal(), random.normal(), random.normal());
    P.row(i) = (p.normalized().array() * Eigen::Array3d(3, 2, 1)).matrix().transpose();
  }
  const SurfaceReconstruction r = reconstruct_surface(P);
  Eigen::MatrixX3i F = r.mesh.faces;
  const UnfoldStatistics s = unfold_boundary(r.mesh.vertices.positions, F);
  EXPECT_EQ(s.folds_before, 0u);
  EXPECT_EQ(s.patches, 0u);
  EXPECT_EQ(F, r.mesh.faces);
}

}  // namespace
}  // namespace scanstation
