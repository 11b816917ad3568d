// The whole station flow end to end on the simulator, for objects with
// concavities and grooves: scan → live boundary → final boundary → six-split
// → exports, measured against each object's true surface, and a replay of
// the recorded session giving the same files byte for byte.
#include "cli_support.h"
#include "core/io/mesh_io.h"
#include "core/mesh_topology.h"
#include "sim/scan_objects.h"
#include "test_support.h"

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

namespace scanstation {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::Outcome;
using test::ScratchFolder;
using test::scanstation;
using test::slurp;

struct FlowCase {
  const char* object;
  double mesh_rms_of_diagonal;  // bound on the boundary's RMS distance to the true surface
};

class StationFlow : public testing::TestWithParam<FlowCase> {};

TEST_P(StationFlow, ClosedGenusZeroThroughAllPointsNearTheTruthAndReplayedByteForByte) {
  const FlowCase c = GetParam();
  ScratchFolder dir;
  std::ofstream(dir / "small.toml") << "[camera]\nbackend = \"sim\"\nwidth = 320\nheight = 240\n"
                                       "[[laser]]\nbackend = \"sim\"\n[[laser]]\nbackend = \"sim\"\n"
                                       "[turntable]\nbackend = \"sim\"\n";
  // 15° steps and every fourth row: a coarse but even sampling, quick.
  const Outcome scan = scanstation("scan --station " + (dir / "small.toml").string() + " --object " + c.object +
                                   " --steps 24 --row-step 4 -o " + (dir / "s").string());
  ASSERT_EQ(scan.exit_code, 0) << scan.err;
  const json report = json::parse(slurp(dir / "s" / "report.json"));
  const json& boundary = report["boundary"];
  test::expect_live_closed_genus_zero(boundary, 24);
  const TriangleMesh mesh = io::read_mesh(dir / "s" / "mesh.ply");
  const MeshTopology t = mesh_topology(mesh);
  EXPECT_TRUE(t.closed && t.oriented);
  EXPECT_EQ(t.genus, 0);
  const json& accuracy = report["accuracy"];
  const double points = accuracy["points"]["rms_of_diagonal"], to_truth = accuracy["mesh"]["to_truth"]["rms_of_diagonal"];
  std::printf("%s: %lld points, RMS to the truth: points %.4f%%, boundary %.3f%% of the diagonal (Hausdorff %.2f%%)\n",
              c.object, report["points"].get<long long>(), 100 * points, 100 * to_truth,
              100 * accuracy["mesh"]["hausdorff_of_diagonal"].get<double>());
  // The acquisition issue's 0.05% of the diagonal holds at 640×480
  // (tests/acquisition); at this half resolution twice that.
  EXPECT_LE(points, 1e-3);
  EXPECT_LE(to_truth, c.mesh_rms_of_diagonal);
  // Where the scan saw the object: the share of the true surface's area
  // with a point within reach of its faces' centroids, counted here by brute
  // force, and the distances there no larger than over the whole.
  const json& seen = accuracy["seen"];
  const double reach = seen["reach"];
  const TriangleMesh truth = sim::scan_object(c.object).on_platter;
  const Eigen::MatrixX3d P = io::read_points(dir / "s" / "points.ply").positions;
  double seen_area = 0, area = 0;
  for (Eigen::Index f = 0; f < truth.face_count(); ++f) {
    const auto& V = truth.vertices.positions;
    const Eigen::Vector3d a = V.row(truth.faces(f, 0)), b = V.row(truth.faces(f, 1)), d = V.row(truth.faces(f, 2));
    const double face_area = 0.5 * (b - a).cross(d - a).norm();
    area += face_area;
    if (((P.rowwise() - ((a + b + d) / 3.0).transpose()).rowwise().squaredNorm().array() <= reach * reach).any())
      seen_area += face_area;
  }
  std::printf("%s: seen %.1f%% of the area within %.2f; Hausdorff there %.2f (mesh), %.2f (smooth)\n", c.object,
              100 * seen["coverage"].get<double>(), reach, seen["mesh"]["hausdorff"].get<double>(),
              seen["smooth"]["hausdorff"].get<double>());
  EXPECT_NEAR(seen["coverage"].get<double>(), seen_area / area, 1e-9);
  EXPECT_GT(seen["coverage"].get<double>(), 0.5);
  EXPECT_LT(seen["coverage"].get<double>(), 1.0);  // the underside stands on the platter
  EXPECT_LE(seen["mesh"]["hausdorff"].get<double>(), accuracy["mesh"]["hausdorff"].get<double>());
  EXPECT_LE(seen["smooth"]["hausdorff"].get<double>(), accuracy["smooth"]["hausdorff"].get<double>());
  // The smooth surface does not bulge: Step 5 moves its control points at
  // most a quarter of a macro edge length on scanned boundaries (the
  // surface's distance from the mesh, per local edge length, adds the
  // patches' own curvature; measured 0.22–0.26 here, 0.6–1.1 with the one
  // edge length the station allowed before).
  // Where the boundary itself folds (slits at waists) so does the surface.
  const json& smoothing = report["smoothing"];
  const double bulge = smoothing["oscillation"]["max_relative"];
  std::printf("%s: smooth surface: largest normal angle %.3g rad, oscillation %.3g, %d edges joined approximately\n",
              c.object, smoothing["g1"]["max_normal_angle"].get<double>(), bulge,
              smoothing["dependent_edges"].get<int>());
  EXPECT_LE(bulge, 0.5);
  // smooth.ply: a density per patch (automatic), one closed genus-0 surface
  // of the faces reported, within the tolerance but for a few bulges.
  const json& tessellation = smoothing["tessellation"];
  std::printf("%s: smooth.ply %lld triangles for %lld patches, %lld above the tolerance\n", c.object,
              tessellation["faces"].get<long long>(), smoothing["patches"].get<long long>(),
              tessellation["patches_above_tolerance"].get<long long>());
  EXPECT_EQ(tessellation["automatic"], true);
  EXPECT_LT(tessellation["patches_above_tolerance"].get<Eigen::Index>(), smoothing["patches"].get<Eigen::Index>() / 100);
  const TriangleMesh smooth = io::read_mesh(dir / "s" / "smooth.ply");
  EXPECT_EQ(smooth.face_count(), tessellation["faces"].get<Eigen::Index>());
  const MeshTopology smooth_topology = mesh_topology(smooth);
  EXPECT_TRUE(smooth_topology.closed && smooth_topology.oriented);
  EXPECT_EQ(smooth_topology.genus.value_or(-1), 0);

  const Outcome replay = scanstation("replay " + (dir / "s").string() + " -o " + (dir / "r").string());
  ASSERT_EQ(replay.exit_code, 0) << replay.err;
  for (const char* file : {"points.ply", "mesh.ply", "smooth.ply", "patches.json", "preview.png"})
    EXPECT_EQ(slurp(dir / "r" / file), slurp(dir / "s" / file)) << file;
}

INSTANTIATE_TEST_SUITE_P(Objects, StationFlow,
                         // Measured: 0.31%, 0.28%, 0.23% (without lines of sight, the
                         // waists bridged: 1.54%, 1.82%, 0.25%).
                         testing::Values(FlowCase{"chalice", 0.006}, FlowCase{"candlestick", 0.006},
                                         FlowCase{"ellipsoid", 0.005}),
                         [](const testing::TestParamInfo<FlowCase>& info) { return std::string(info.param.object); });

}  // namespace
}  // namespace scanstation
