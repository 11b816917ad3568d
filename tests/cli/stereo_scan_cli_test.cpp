// `scanstation scan --rig stereo` end to end on the simulated stereo station
// (two simulated cameras, the projector on a simulated GPIO line, the
// stepper turntable): session recorded step by step, the boundary grown
// live from each step's stereo points, the results measured against the
// object's true surface, a replay giving the same files byte for byte, an
// interrupted scan resumed to the same result, and bad input refused.
#include "cli_support.h"
#include "core/io/mesh_io.h"
#include "core/mesh_topology.h"
#include "test_support.h"

#include <gmock/gmock.h>
#include <nlohmann/json.hpp>

namespace scanstation {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::Outcome;
using test::progress_events;
using test::ScratchFolder;
using test::scanstation;
using test::slurp;

// Small for CI: a few steps, every eighth pixel of every eighth row, a
// light tessellation; the built-in stereo station's 640×480 cameras (at
// 320×240 the points are 2–5 times noisier).
std::string stereo_scan(const std::string& object, int steps, const fs::path& out, const std::string& more = "") {
  return "--progress json scan --rig stereo --backend sim --object " + object + " --steps " + std::to_string(steps) +
         " --pixel-step 8 --density 1 " + more + " -o " + out.string();
}

std::string replay(const fs::path& session, const fs::path& out, const std::string& more = "") {
  return "replay " + session.string() + " --density 1 " + more + " -o " + out.string();
}

struct StereoCase {
  const char* object;
  double points_rms_of_diagonal;  // bounds on the RMS distance to the true surface
  double mesh_rms_of_diagonal;
};

class StereoScan : public testing::TestWithParam<StereoCase> {};

TEST_P(StereoScan, ClosedGenusZeroThroughAllPointsNearTheTruthAndReplayedByteForByte) {
  const StereoCase c = GetParam();
  ScratchFolder dir;
  constexpr int kSteps = 6;
  const Outcome scan = scanstation(stereo_scan(c.object, kSteps, dir / "s"));
  ASSERT_EQ(scan.exit_code, 0) << scan.err;

  // Recorded as a stereo session: the pair with the dots and the colour
  // frame without them, every step.
  const json manifest = json::parse(slurp(dir / "s" / "manifest.json"));
  EXPECT_EQ(manifest["rig"], "stereo");
  EXPECT_TRUE(manifest["geometry"].contains("right_camera"));
  EXPECT_EQ(manifest["station"]["projector"], "sim");
  for (int step = 0; step < kSteps; ++step)
    for (const char* frame : {"left_dots", "right_dots", "left"}) {
      char name[64];
      std::snprintf(name, sizeof name, "step_%04d_%s.png", step, frame);
      EXPECT_TRUE(fs::exists(dir / "s" / "frames" / name)) << name;
    }

  // Live: one step and one boundary event per step, the points growing.
  const std::vector<json> steps = progress_events(scan.err, "step");
  const std::vector<json> live = progress_events(scan.err, "boundary");
  ASSERT_EQ(steps.size(), std::size_t(kSteps)) << scan.err;
  ASSERT_EQ(live.size(), std::size_t(kSteps));
  for (int k = 0; k < kSteps; ++k) {
    EXPECT_NEAR(steps[std::size_t(k)]["angle_deg"].get<double>(), 360.0 * k / kSteps, 0.1);
    if (k > 0) {
      EXPECT_GT(live[std::size_t(k)]["points"], live[std::size_t(k - 1)]["points"]);
    }
  }

  const json report = json::parse(slurp(dir / "s" / "report.json"));
  EXPECT_EQ(report["rig"], "stereo");
  EXPECT_EQ(report["complete"], true);
  const json& boundary = report["boundary"];
  test::expect_live_closed_genus_zero(boundary, kSteps);
  EXPECT_EQ(boundary["distinct_points"].get<long long>() + boundary["duplicates_merged"].get<long long>(),
            report["points"].get<long long>());
  const TriangleMesh mesh = io::read_mesh(dir / "s" / "mesh.ply");
  const MeshTopology t = mesh_topology(mesh);
  EXPECT_TRUE(t.closed && t.oriented);
  EXPECT_EQ(t.genus, 0);

  const json& accuracy = report["accuracy"];
  const double diagonal = accuracy["truth_diagonal"];
  const double points = accuracy["points"]["rms_of_diagonal"], to_truth = accuracy["mesh"]["to_truth"]["rms_of_diagonal"];
  std::printf("%s: %lld points; RMS to the truth: points %.3f%% of the diagonal (%.3f mm), boundary %.3f%% "
              "(%.3f mm)\n",
              c.object, report["points"].get<long long>(), 100 * points, points * diagonal, 100 * to_truth,
              to_truth * diagonal);
  EXPECT_LE(points, c.points_rms_of_diagonal);
  EXPECT_LE(to_truth, c.mesh_rms_of_diagonal);

  const Outcome replayed = scanstation(replay(dir / "s", dir / "r"));
  ASSERT_EQ(replayed.exit_code, 0) << replayed.err;
  for (const char* file : {"points.ply", "mesh.ply", "smooth.ply", "patches.json"})
    EXPECT_EQ(slurp(dir / "r" / file), slurp(dir / "s" / file)) << file;
}

// Stereo depth noise grows with the square of the distance: at 640×480 the
// points lie within about 0.3% of the diagonal of the truth (RMS), the laser
// rig's within 0.1%. The candlestick's grooves are concavities the cameras
// see from the side.
INSTANTIATE_TEST_SUITE_P(Objects, StereoScan,
                         testing::Values(StereoCase{"ellipsoid", 0.005, 0.01}, StereoCase{"candlestick", 0.005, 0.01}),
                         [](const testing::TestParamInfo<StereoCase>& info) { return std::string(info.param.object); });

TEST(StereoScanSession, InterruptedAndResumedGivesTheSameResultAndDamageIsReported) {
  ScratchFolder dir;
  const Outcome whole = scanstation(stereo_scan("sphere", 3, dir / "whole"));
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  const Outcome first = scanstation(stereo_scan("sphere", 3, dir / "parts", "--stop-after 1"));
  ASSERT_EQ(first.exit_code, 0) << first.err;
  EXPECT_THAT(first.out, testing::HasSubstr("stopped after 1 of 3"));
  // --resume takes the rig, object and steps from the session.
  const Outcome second = scanstation("scan --resume --density 1 -o " + (dir / "parts").string());
  ASSERT_EQ(second.exit_code, 0) << second.err;
  for (const char* file : {"points.ply", "mesh.ply"})
    EXPECT_EQ(slurp(dir / "parts" / file), slurp(dir / "whole" / file)) << file;
  const Outcome wrong_rig = scanstation("scan --resume --rig turntable -o " + (dir / "parts").string());
  EXPECT_EQ(wrong_rig.exit_code, 1);
  EXPECT_THAT(wrong_rig.err, testing::HasSubstr("recorded with the stereo rig"));

  // Laser parameters do not apply to a stereo session.
  const Outcome laser_options = scanstation(replay(dir / "whole", dir / "r1", "--row-step 2"));
  EXPECT_EQ(laser_options.exit_code, 1);
  EXPECT_THAT(laser_options.err, testing::HasSubstr("stereo session"));

  // Cell means: the same pixels, each point the mean of its cell on one
  // surface, nearer the true sphere; the least spacing thins the stereo
  // stream as the laser's.
  const Outcome mean = scanstation(replay(dir / "whole", dir / "mean", "--cell-mean --min-spacing 1"));
  ASSERT_EQ(mean.exit_code, 0) << mean.err;
  const json alone = json::parse(slurp(dir / "whole" / "report.json")), averaged = json::parse(slurp(dir / "mean" / "report.json"));
  EXPECT_EQ(averaged["parameters"]["cell_mean"], true);
  EXPECT_EQ(alone["parameters"]["cell_mean"], false);
  EXPECT_GT(averaged["points_thinned"].get<long long>(), 0);
  const auto rms = [](const json& r) { return r["accuracy"]["points"]["rms"].get<double>(); };
  EXPECT_LT(rms(averaged), 0.9 * rms(alone)) << rms(averaged) << " against " << rms(alone);

  // A lost right frame skips its step, named; the rest is replayed.
  fs::remove(dir / "whole" / "frames" / "step_0001_right_dots.png");
  const Outcome damaged = scanstation(replay(dir / "whole", dir / "r2"));
  ASSERT_EQ(damaged.exit_code, 0) << damaged.err;
  EXPECT_THAT(damaged.err, testing::HasSubstr("step_0001_right_dots.png: missing"));
  const json report = json::parse(slurp(dir / "r2" / "report.json"));
  EXPECT_EQ(report["steps"]["used"], 2);
  EXPECT_EQ(report["boundary"]["topology"]["genus"], 0);
}

TEST(StereoScanInput, MissingOrMismatchedStereoRolesAreRefusedClearly) {
  ScratchFolder dir;
  const auto refused = [&](const std::string& toml, const std::string& more,
                           std::initializer_list<std::string> message) {
    const fs::path station = dir / "station.toml";
    std::ofstream(station) << toml;
    const Outcome r = scanstation("scan --rig stereo --station " + station.string() + " --steps 2 " + more + " -o " +
                                  (dir / "s").string());
    EXPECT_EQ(r.exit_code, 1) << toml;
    for (const std::string& part : message) EXPECT_THAT(r.err, testing::HasSubstr(part)) << toml;
    EXPECT_FALSE(fs::exists(dir / "s" / "manifest.json")) << "no session started";
  };
  const std::string left = "[camera]\nbackend = \"sim\"\nwidth = 320\nheight = 240\n";
  refused(left, "", {"station.toml", "no [right_camera]", "second camera"});
  refused(left + "[right_camera]\nbackend = \"sim\"\nwidth = 640\nheight = 480\n", "",
          {"right_camera streams 640x480, camera 320x240", "same size"});
  refused(left + "[right_camera]\nbackend = \"sim\"\nwidth = 320\nheight = 240\n[projector]\nbackend = \"gpio\"\n", "",
          {"station.toml:", "projector.line"});
  refused(left + "[right_camera]\nwidht = 320\n", "", {"station.toml:", "right_camera.widht: unknown key"});
  const std::string stereo = left + "[right_camera]\nbackend = \"sim\"\nwidth = 320\nheight = 240\n";
  refused(stereo, "--row-step 2", {"--rig stereo", "laser processing options"});
  refused(stereo, "--calibration " + (dir / "cal.json").string(), {"cal.json does not exist", "calibrate stereo"});
  const Outcome pixel_step = scanstation("scan --rig turntable --pixel-step 2 -o " + (dir / "t").string());
  EXPECT_EQ(pixel_step.exit_code, 1);
  EXPECT_THAT(pixel_step.err, testing::HasSubstr("--pixel-step: a stereo option"));
}

}  // namespace
}  // namespace scanstation
