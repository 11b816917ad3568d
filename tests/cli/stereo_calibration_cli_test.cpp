// The stereo rig calibrated through the simulated stereo station's devices
// and scanned with: `calibrate stereo --backend sim` (both cameras, their
// relative pose, the turntable axis seen by the left camera) against the
// simulator's truth, `scan --rig stereo --calibration` close to the scan with
// the true cameras, a replay of the true-camera session with the calibration
// giving the calibrated scan's points byte for byte, stale, mismatched and
// incomplete calibrations refused, and a replay with new stereo parameters.
#include "cli_support.h"
#include "test_support.h"

#include <gmock/gmock.h>
#include <nlohmann/json.hpp>

namespace scanstation {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::Outcome;
using test::ScratchFolder;
using test::scanstation;
using test::slurp;

// Small for CI: four steps, every eighth pixel of every eighth row.
std::string stereo_scan(const fs::path& out, const std::string& more = "") {
  return "--progress none scan --rig stereo --backend sim --object ellipsoid --steps 4 --pixel-step 8 --density 1 " +
         more + " -o " + out.string();
}

json report_of(const fs::path& folder) { return json::parse(slurp(folder / "report.json")); }

double points_rms(const json& report) { return report["accuracy"]["points"]["rms_of_diagonal"].get<double>(); }

TEST(StereoCalibrationCli, SimulatedPairMatchesTheTruthAndScansAsTheTrueCamerasDo) {
  ScratchFolder dir;
  const fs::path cal = dir / "cal.json";
  Outcome r = scanstation("--progress none calibrate stereo --backend sim -o " + cal.string() + " --report " +
                          (dir / "calibrate.json").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, testing::HasSubstr("placed on the turntable"));

  // The limits: focal length within 0.5%, axis within 0.1°; the
  // pair's relative pose close (baseline 0.5%, rotation 0.1°).
  const json result = json::parse(slurp(dir / "calibrate.json"))["result"];
  const json& truth = result["truth"];
  std::printf("stereo calibration against the truth: %s\n", truth.dump().c_str());
  EXPECT_EQ(result["pairs"]["used"], result["pairs"]["given"]);
  EXPECT_LT(result["residuals"]["rms_px"].get<double>(), 0.3);
  for (const char* key : {"left_fx_error", "left_fy_error", "right_fx_error", "right_fy_error", "baseline_error"})
    EXPECT_LT(std::abs(truth[key].get<double>()), 0.005) << key;
  EXPECT_LT(truth["rotation_error_deg"].get<double>(), 0.1);
  EXPECT_LT(truth["translation_direction_error_deg"].get<double>(), 0.5);
  EXPECT_LT(truth["axis_error_deg"].get<double>(), 0.1);
  EXPECT_LT(truth["left_orientation_error_deg"].get<double>(), 0.2);  // includes the turn about the axis
  EXPECT_LT(truth["left_centre_error_mm"].get<double>(), 0.5);
  EXPECT_LT(truth["right_centre_error_mm"].get<double>(), 0.5);

  // The file: the built-in stereo station's fingerprint with its right
  // camera, the pair placed on the turntable, per-view and overall residuals.
  const json file = json::parse(slurp(cal));
  EXPECT_EQ(file["station"]["name"], "sim-stereo");
  EXPECT_EQ(file["station"]["devices"]["right_camera"]["width"], 640);
  EXPECT_EQ(file["stereo"]["pose"], "station");
  EXPECT_EQ(file["stereo"]["residuals"]["per_view_rms_px"].size(), file["stereo"]["pairs"].get<std::size_t>());
  EXPECT_TRUE(file["stereo"]["turntable"]["residuals"].contains("rms"));

  // Scanned with the calibration: as close to the truth as with the true cameras.
  r = scanstation(stereo_scan(dir / "calibrated", "--calibration " + cal.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = scanstation(stereo_scan(dir / "truth"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json calibrated = report_of(dir / "calibrated"), true_cameras = report_of(dir / "truth");
  EXPECT_EQ(calibrated["geometry"]["source"], cal.string());
  EXPECT_EQ(calibrated["geometry"]["calibration"]["fingerprint"], file["station"]["fingerprint"]);
  EXPECT_EQ(true_cameras["geometry"]["source"], "simulator truth");
  std::printf("ellipsoid, 4 steps: points RMS %.3f%% of the diagonal calibrated, %.3f%% with the true cameras\n",
              100 * points_rms(calibrated), 100 * points_rms(true_cameras));
  EXPECT_LE(points_rms(calibrated), 0.005);
  EXPECT_LE(points_rms(calibrated), 1.1 * points_rms(true_cameras));
  EXPECT_EQ(calibrated["boundary"]["topology"]["genus"], 0);

  // The same frames replayed with the calibration give the calibrated scan's points.
  r = scanstation("--progress none replay " + (dir / "truth").string() + " --density 1 --calibration " + cal.string() +
                  " -o " + (dir / "recalibrated").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(slurp(dir / "recalibrated" / "points.ply"), slurp(dir / "calibrated" / "points.ply"));

  // New stereo parameters on replay: denser and still near the truth, the
  // report naming them; the same parameters again give the same bytes.
  const std::string denser = " --density 1 --pixel-step 4 --block-size 7 --uniqueness 5 -o ";
  r = scanstation("--progress none replay " + (dir / "truth").string() + denser + (dir / "denser").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = scanstation("--progress none replay " + (dir / "truth").string() + denser + (dir / "denser2").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json dense = report_of(dir / "denser");
  EXPECT_EQ(dense["parameters"]["pixel_step"], 4);
  EXPECT_EQ(dense["parameters"]["block_size"], 7);
  EXPECT_EQ(dense["parameters"]["uniqueness_ratio"], 5);
  EXPECT_GT(dense["points"].get<long long>(), 3 * true_cameras["points"].get<long long>());
  EXPECT_LE(points_rms(dense), 0.005);
  EXPECT_EQ(slurp(dir / "denser" / "points.ply"), slurp(dir / "denser2" / "points.ply"));

  // Refused with the laser rig's messages: stale, incomplete, other devices.
  const auto refused = [&](const json& edited, const std::string& more, std::initializer_list<std::string> message) {
    const fs::path path = dir / "edited.json";
    std::ofstream(path) << edited.dump(2);
    const Outcome o = scanstation(stereo_scan(dir / "refused", "--calibration " + path.string() + " " + more));
    EXPECT_EQ(o.exit_code, 1) << edited.dump().substr(0, 200);
    for (const std::string& part : message) EXPECT_THAT(o.err, testing::HasSubstr(part));
    EXPECT_FALSE(fs::exists(dir / "refused" / "manifest.json")) << "no session started";
  };
  json stale = file;
  stale["stereo"]["date"] = "2020-01-01T00:00:00Z";
  refused(stale, "", {"is stale: its stereo.date is", "calibrate stereo --force", "--calibration-max-age"});
  json unposed = file;
  unposed["stereo"].erase("turntable");
  unposed["stereo"]["pose"] = "camera";
  refused(unposed, "", {"does not place the stereo pair on the turntable", "calibrate stereo"});
  json laser_only = file;
  laser_only.erase("stereo");
  refused(laser_only, "", {"has no stereo calibration", "calibrate stereo"});
  const fs::path small = dir / "small.toml";
  std::ofstream(small) << "name = \"sim-stereo\"\n[camera]\nbackend = \"sim\"\nwidth = 320\nheight = 240\n"
                       << "[right_camera]\nbackend = \"sim\"\nwidth = 320\nheight = 240\n";
  refused(file, "--station " + small.string(),
          {"made for other devices", "right_camera.width: calibrated 640, station 320"});
}

TEST(StereoCalibrationCli, StereoOptionsBelongToStereo) {
  ScratchFolder dir;
  const Outcome r = scanstation("scan --rig turntable --block-size 7 -o " + (dir / "t").string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, testing::HasSubstr("--block-size: a stereo option"));
  // The station description's calibration file is the stereo scan's default.
  std::ofstream(dir / "station.toml") << "calibration = \"gone.json\"\n[camera]\nbackend = \"sim\"\n"
                                      << "[right_camera]\nbackend = \"sim\"\n";
  const Outcome gone = scanstation("scan --rig stereo --station " + (dir / "station.toml").string() + " -o " +
                                   (dir / "s").string());
  EXPECT_EQ(gone.exit_code, 1);
  EXPECT_THAT(gone.err, testing::HasSubstr("gone.json does not exist (named by the station description"));
  EXPECT_THAT(gone.err, testing::HasSubstr("calibrate stereo"));
  const Outcome odd = scanstation("replay " + (dir / "t").string() + " --num-disparities 40");
  EXPECT_NE(odd.exit_code, 0);
  EXPECT_THAT(odd.err, testing::HasSubstr("a multiple of 16"));
}

}  // namespace
}  // namespace scanstation
