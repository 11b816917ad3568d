// The whole station flow end to end on the simulator, for objects with
// concavities and grooves: scan → live boundary → final boundary → six-split
// → exports, measured against each object's true surface, and a replay of
// the recorded session giving the same files byte for byte.
#include "cli_support.h"
#include "core/io/mesh_io.h"
#include "core/mesh_topology.h"
#include "test_support.h"

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
  // Grown live step by step; the result carves what the camera saw first.
  EXPECT_EQ(boundary["built"], "from scratch, lines of sight carved first");
  EXPECT_EQ(boundary["live"]["steps"], 24);
  EXPECT_GT(boundary["sight_line_cells"].get<int>(), 0);
  EXPECT_EQ(boundary["topology"]["closed"], true);
  EXPECT_EQ(boundary["topology"]["genus"], 0);
  EXPECT_EQ(boundary["topology"]["manifold"], true);
  EXPECT_EQ(boundary["all_on_boundary"], true);
  EXPECT_EQ(boundary["vertices"], boundary["distinct_points"]);
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
  // The smooth surface does not bulge: Step 5 moves its control points at
  // most one macro edge length on scanned boundaries (the surface's distance
  // from the mesh, per local edge length, adds the patches' own curvature).
  // Where the boundary itself folds (slits at waists) so does the surface.
  const json& smoothing = report["smoothing"];
  const double bulge = smoothing["oscillation"]["max_relative"];
  std::printf("%s: smooth surface: largest normal angle %.3g rad, oscillation %.3g, %d edges joined approximately\n",
              c.object, smoothing["g1"]["max_normal_angle"].get<double>(), bulge,
              smoothing["dependent_edges"].get<int>());
  EXPECT_LE(bulge, 1.5);

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
