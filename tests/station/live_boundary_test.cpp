// The live boundary of the station flow: a closed boundary through every
// point after every step, snapshots, and the stream digest that decides
// whether a scan's live boundary is the final one.
#include "core/io/mesh_io.h"
#include "core/mesh_topology.h"
#include "sim/arrival_order.h"
#include "sim/sampling.h"
#include "sim/scan_objects.h"
#include "sim/shapes.h"
#include "acquisition/stereo_reconstruction.h"
#include "sim/stereo_rig.h"
#include "station/live_boundary.h"
#include "test_support.h"

#include <gtest/gtest.h>
#include <numbers>
#include <opencv2/core.hpp>

namespace scanstation {
namespace {

namespace fs = std::filesystem;
using station::LiveBoundary;

// The points of `mesh`'s surface cut into `steps` wedges by angle about the
// axis, one "laser" cloud per step, as a turntable delivers them.
std::vector<std::vector<acquisition::LaserScanPoints>> wedges(const TriangleMesh& mesh, int count, int steps) {
  const Eigen::MatrixX3d P = sim::sample_surface(mesh, count, 7).positions;
  const std::vector<Eigen::Index> order = sim::turntable_order(P);
  std::vector<std::vector<acquisition::LaserScanPoints>> out(static_cast<std::size_t>(steps));
  for (int s = 0; s < steps; ++s) {
    const std::size_t from = order.size() * s / steps, to = order.size() * (s + 1) / steps;
    acquisition::LaserScanPoints cloud;
    cloud.cloud.positions.resize(static_cast<Eigen::Index>(to - from), 3);
    for (std::size_t i = from; i < to; ++i) cloud.cloud.positions.row(Eigen::Index(i - from)) = P.row(order[i]);
    out[static_cast<std::size_t>(s)].push_back(cloud);
  }
  return out;
}

TEST(LiveBoundary, EveryStepHasAClosedGenusZeroBoundaryThroughAllPoints) {
  const auto steps = wedges(sim::scan_object("chalice").on_platter, 3000, 12);
  test::ScratchFolder dir;
  station::LiveBoundaryOptions options;
  options.snapshot_every = 4;
  options.snapshot_folder = dir / "snap";
  options.placement.scale = 2.0;  // snapshots come out in the object's own coordinates
  LiveBoundary live(options);
  Eigen::Index points = 0;
  for (int s = 0; s < 12; ++s) {
    const station::LiveStep step = live.add_step(s, 30.0 * s, steps[static_cast<std::size_t>(s)]);
    points += step.step_points;
    EXPECT_EQ(step.points, points);
    EXPECT_EQ(step.snapshot.has_value(), (s + 1) % 4 == 0);
    if (s == 0) continue;  // one wedge may still be flat at its start
    // The constricted boundary: a closed genus-0 triangulation through every
    // point constriction reached; the pending ones are brought on by the
    // augmentation of surface() (§5.4).
    EXPECT_EQ(step.all_on_boundary, step.pending == 0);
    EXPECT_EQ(step.boundary_faces, 2 * (step.points - Eigen::Index(step.pending)) - 4) << "step " << s;
    const SurfaceReconstruction now = live.constriction().surface();
    EXPECT_TRUE(now.statistics.all_on_boundary) << "step " << s;
    EXPECT_EQ(now.mesh.vertex_count(), step.points);
    EXPECT_EQ(now.mesh.face_count(), 2 * step.points - 4);
  }
  const TriangleMesh snapshot = io::read_mesh(dir / "snap" / "boundary-step-0011.ply");
  const TriangleMesh final_mesh = live.constriction().boundary();
  EXPECT_EQ(snapshot.faces, final_mesh.faces);
  EXPECT_TRUE(snapshot.vertices.positions.isApprox(final_mesh.vertices.positions / 2.0));
  const MeshTopology t = mesh_topology(final_mesh.faces, final_mesh.vertex_count());
  EXPECT_TRUE(t.closed);
  EXPECT_EQ(t.genus, 0);
  EXPECT_EQ(final_mesh.vertex_count(), 3000);
}

TEST(LiveBoundary, DigestTellsWhetherTwoRunsWereFedTheSamePoints) {
  const auto steps = wedges(sim::scan_object("sphere").on_platter, 400, 4);
  station::StreamDigest a, b, c;
  for (const auto& s : steps) a.add(s), b.add(s);
  EXPECT_EQ(a.value(), b.value());
  auto changed = steps;
  changed[2][0].cloud.positions(5, 1) = std::nextafter(changed[2][0].cloud.positions(5, 1), 1e9);
  for (const auto& s : changed) c.add(s);
  EXPECT_NE(a.value(), c.value());
  station::StreamDigest reordered;
  for (int s = 3; s >= 0; --s) reordered.add(steps[static_cast<std::size_t>(s)]);
  EXPECT_NE(a.value(), reordered.value());
}

}  // namespace
}  // namespace scanstation

namespace scanstation {
namespace {

// Points from the stereo pipeline feed the live boundary the same way: one
// batch per turntable view, noisy and overlapping, still a closed genus-0
// boundary through every point after every view.
TEST(LiveBoundary, GrowsFromStereoViewsToo) {
  constexpr double platter_radius = 60.0, radius = 25.0;
  TriangleMesh sphere = sim::ellipsoid(Eigen::Vector3d::Constant(radius), 5);
  sphere.vertices.positions.col(2).array() += radius;
  const sim::StereoRig rig = sim::stereo_rig(2 * radius, platter_radius, 160, 120);
  const sim::SceneRenderer renderer(sim::stereo_scene(sphere, rig, platter_radius, true));
  acquisition::StereoStation station = acquisition::stereo_station(rig.left, rig.right);
  acquisition::StereoReconstructionOptions options;
  options.matcher = acquisition::fit_disparity_range(station, platter_radius, 2 * radius, options.matcher);
  options.maximum_radius = radius + 2.0;
  LiveBoundary live;
  Eigen::Index rows = 0;
  for (int v = 0; v < 6; ++v) {
    const double angle = 2.0 * std::numbers::pi * v / 6;
    const cv::Mat left = renderer.expose(renderer.cast(rig.left, angle), {}, 2 * static_cast<std::uint64_t>(v));
    const cv::Mat right = renderer.expose(renderer.cast(rig.right, angle), {}, 2 * static_cast<std::uint64_t>(v) + 1);
    const acquisition::LaserScanPoints view = acquisition::stereo_view_points(station, left, right, angle, options);
    ASSERT_GT(view.cloud.size(), 100) << "view " << v;
    rows += view.cloud.size();
    const station::LiveStep step = live.add_step(v, angle * 180 / std::numbers::pi, {view});
    EXPECT_EQ(step.step_points, view.cloud.size());
    if (v == 0) continue;
    EXPECT_EQ(step.boundary_faces, 2 * (step.points - Eigen::Index(step.pending)) - 4) << "view " << v;
  }
  const SurfaceReconstruction final_surface = live.constriction().surface();
  EXPECT_TRUE(final_surface.statistics.all_on_boundary);
  const MeshTopology t = mesh_topology(final_surface.mesh);
  EXPECT_TRUE(t.closed && t.oriented);
  EXPECT_EQ(t.genus, 0);
  EXPECT_EQ(final_surface.mesh.vertex_count() + final_surface.statistics.duplicates_merged, rows);
}

}  // namespace
}  // namespace scanstation
