// The live boundary of the station flow: a closed boundary through every
// point after every step, snapshots, and the stream digest that decides
// whether a scan's live boundary is the final one.
#include "core/io/mesh_io.h"
#include "core/mesh_topology.h"
#include "sim/arrival_order.h"
#include "sim/sampling.h"
#include "sim/scan_objects.h"
#include "station/live_boundary.h"
#include "test_support.h"

#include <gtest/gtest.h>

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
