// `scanstation scan` with a calibration, end to end on the simulator:
// calibrate camera → turntable → laser on the station's simulated rig (views
// captured through its simulated devices, the accuracy checked), scan
// the sphere with that file (the same rig: one rig per station), and measure
// the points against the true sphere; the refusals (other devices, an
// incomplete file, a stale one, a missing one) name the field and the fix.
#include "cli_support.h"
#include "core/io/mesh_io.h"
#include "test_support.h"

#include <ctime>
#include <iomanip>
#include <sstream>
#include <nlohmann/json.hpp>

namespace scanstation {
namespace {

using test::Outcome;
using test::scanstation;
using test::ScratchFolder;
using test::slurp;
namespace fs = std::filesystem;
using nlohmann::json;

fs::path write_station(const ScratchFolder& dir, const std::string& name, int width, int height,
                       const std::string& extra = "") {
  const fs::path file = dir / (name + ".toml");
  std::ofstream(file) << "name = \"bench\"\n" << extra << "[camera]\nbackend = \"sim\"\nwidth = " << width
                      << "\nheight = " << height
                      << "\n[[laser]]\nbackend = \"sim\"\n[[laser]]\nbackend = \"sim\"\n"
                      << "[turntable]\nbackend = \"sim\"\n";
  return file;
}

void write_json(const fs::path& file, const json& document) { std::ofstream(file) << document.dump(2); }

// A short scan (one step of four) on `station` with `arguments`.
Outcome short_scan(const fs::path& station, const std::string& arguments, const fs::path& out) {
  return scanstation("--progress none scan --station " + station.string() + " --steps 4 --stop-after 1 " + arguments +
                     " -o " + out.string());
}

// A station with a real camera scans only with its calibration: without one,
// or with the simulator's truth, it is refused before anything is recorded
// or any device opened (the camera named here does not exist).
TEST(ScanWithCalibration, RealStationNeedsItsCalibrationFile) {
  ScratchFolder dir;
  const fs::path station = dir / "real.toml";
  std::ofstream(station) << "name = \"bench\"\n[camera]\nbackend = \"v4l2\"\ndevice = \"/dev/video-absent\"\n"
                         << "[[laser]]\nbackend = \"sim\"\n[turntable]\nbackend = \"sim\"\n";
  const Outcome none = short_scan(station, "", dir / "a");
  EXPECT_EQ(none.exit_code, 1);
  EXPECT_THAT(none.err, testing::HasSubstr("no calibration is given"));
  EXPECT_THAT(none.err, testing::HasSubstr("scanstation calibrate camera"));
  EXPECT_FALSE(fs::exists(dir / "a"));
  const Outcome truth = short_scan(station, "--calibration sim-truth", dir / "b");
  EXPECT_EQ(truth.exit_code, 1);
  EXPECT_THAT(truth.err, testing::HasSubstr("only a simulated station has a true geometry"));
  const Outcome missing = short_scan(station, "--calibration " + (dir / "none.json").string(), dir / "c");
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_THAT(missing.err, testing::HasSubstr("none.json does not exist"));
  EXPECT_FALSE(fs::exists(dir / "c"));
}

// One test, so that the expensive part — calibrating a 640×480 station and
// scanning the sphere at the default 36 steps — runs once under ctest.
TEST(ScanWithCalibration, CalibratedSphereWithinTheBudgetAndBadCalibrationsRefused) {
  ScratchFolder dir;
  const fs::path station = write_station(dir, "station", 640, 480);
  const fs::path calibration = dir / "calibration.json", session = dir / "session";
  for (const char* part : {"camera", "turntable", "laser"}) {
    const Outcome r = scanstation(std::string("--progress none calibrate ") + part + " --backend sim --station " +
                                  station.string() + " -o " + calibration.string() + " --report " +
                                  (dir / (std::string(part) + ".json")).string());
    ASSERT_EQ(r.exit_code, 0) << part << ": " << r.err;
  }
  {
    SCOPED_TRACE("the issue's accuracy, views captured through the simulated devices");
    const json camera = json::parse(slurp(dir / "camera.json"))["result"]["truth"];
    const json turntable = json::parse(slurp(dir / "turntable.json"))["result"]["truth"];
    const json lasers = json::parse(slurp(dir / "laser.json"))["result"]["lasers"];
    std::printf("640x480 calibration: camera %s; turntable %s; lasers %s, %s\n", camera.dump().c_str(),
                turntable.dump().c_str(), lasers[0]["truth"].dump().c_str(), lasers[1]["truth"].dump().c_str());
    // Measured: fx +0.003%, fy -0.006%, axis 0.065°, planes 0.014° and 0.015°.
    EXPECT_LT(std::abs(camera["fx_error"].get<double>()), 0.005);
    EXPECT_LT(std::abs(camera["fy_error"].get<double>()), 0.005);
    EXPECT_LT(turntable["axis_error_deg"].get<double>(), 0.1);
    ASSERT_EQ(lasers.size(), 2u);
    for (const json& laser : lasers) EXPECT_LT(laser["truth"]["normal_error_deg"].get<double>(), 0.1);
  }
  const Outcome scan = scanstation("--progress none scan --station " + station.string() + " --calibration " +
                                   calibration.string() + " --object sphere -o " + session.string());
  ASSERT_EQ(scan.exit_code, 0) << scan.err;
  {
    SCOPED_TRACE("accuracy and manifest");
    const PointCloud points = io::read_points(session / "points.ply");
    const Eigen::MatrixX3d& P = points.positions;
    ASSERT_GT(P.rows(), 10000);
    const Eigen::Vector3d centre{6.0, -4.0, 30.0};  // sim/scan_objects.cpp: the built-in sphere
    const Eigen::VectorXd distance = ((P.rowwise() - centre.transpose()).rowwise().norm().array() - 30.0).abs();
    const double rms = std::sqrt(distance.squaredNorm() / static_cast<double>(P.rows()));
    const double budget = 5e-4 * 60.0 * std::sqrt(3.0);  // 0.05% of the sphere's bounding-box diagonal
    const json report = json::parse(slurp(session / "report.json"));
    std::printf("calibrated scan of the sphere: %ld points, RMS %.4f mm (budget %.4f); laser agreement %s\n",
                static_cast<long>(P.rows()), rms, budget, report["laser_agreement"].dump().c_str());
    // Measured: RMS 0.036 mm with the calibrated geometry, 0.018 mm with the
    // simulator's truth on the same frames (docs/design.md).
    EXPECT_LE(rms, budget);

    const json manifest = json::parse(slurp(session / "manifest.json"));
    const json file = json::parse(slurp(calibration));
    EXPECT_EQ(manifest["geometry"]["source"], calibration.string());
    EXPECT_EQ(manifest["geometry"]["calibration"]["fingerprint"], file["station"]["fingerprint"]);
    EXPECT_EQ(manifest["geometry"]["calibration"]["updated"], file["updated"]);
    EXPECT_EQ(manifest["geometry"]["calibration"]["dates"]["lasers"].size(), 2u);
    EXPECT_EQ(manifest["geometry"]["camera"], file["camera"]["geometry"]);
    // The default 36 steps: the lasers' agreement is checked, and calibrated planes agree.
    EXPECT_TRUE(report["laser_agreement"]["checked"].get<bool>()) << report["laser_agreement"];
    EXPECT_TRUE(report["laser_agreement"]["agree"].get<bool>()) << report["laser_agreement"];
    EXPECT_THAT(scan.out, testing::HasSubstr("lasers 0 and 1 agree: laser 0's cloud lies "));
  }
  {
    SCOPED_TRACE("the station description names its calibration");
      fs::copy_file(calibration, dir / "cal.json");
    const fs::path named = write_station(dir, "named", 640, 480, "calibration = \"cal.json\"\n");
    const Outcome r = short_scan(named, "", dir / "s");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(json::parse(slurp(dir / "s" / "manifest.json"))["geometry"]["source"], (dir / "cal.json").string());
    // --calibration sim-truth overrides it on the simulator.
    const Outcome truth = short_scan(named, "--calibration sim-truth", dir / "t");
    ASSERT_EQ(truth.exit_code, 0) << truth.err;
    EXPECT_EQ(json::parse(slurp(dir / "t" / "manifest.json"))["geometry"]["source"], "simulator truth");
    // A station naming a file that is not there.
    const fs::path missing = write_station(dir, "missing", 640, 480, "calibration = \"gone.json\"\n");
    const Outcome gone = short_scan(missing, "", dir / "g");
    EXPECT_EQ(gone.exit_code, 1);
    EXPECT_THAT(gone.err, testing::HasSubstr("gone.json does not exist (named by the station description"));
    EXPECT_THAT(gone.err, testing::HasSubstr("scanstation calibrate"));
  }
  {
    SCOPED_TRACE("refusals");
    // Another camera size: the field that differs is named.
    Outcome r = short_scan(write_station(dir, "small", 320, 240), "--calibration " + calibration.string(), dir / "a");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_THAT(r.err, testing::HasSubstr("camera.width: calibrated 640, station 320"));
    EXPECT_FALSE(fs::exists(dir / "a" / "manifest.json"));

    // No laser planes: the command that provides them is named.
    json incomplete = json::parse(slurp(calibration));
    incomplete.erase("lasers");
    write_json(dir / "incomplete.json", incomplete);
    r = short_scan(station, "--calibration " + (dir / "incomplete.json").string(), dir / "b");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_THAT(r.err, testing::HasSubstr("has no plane for laser 0: run `scanstation calibrate laser`"));

    // Forty days after the camera part was made the calibration is stale (30
    // days accepted by default), unless the operator accepts its age. The
    // scan's "now" honours SOURCE_DATE_EPOCH, set from the file's own date.
    std::tm made{};
    std::istringstream(json::parse(slurp(calibration))["camera"]["date"].get<std::string>()) >>
        std::get_time(&made, "%Y-%m-%dT%H:%M:%SZ");
    const long long later = static_cast<long long>(timegm(&made)) + 40 * 86400;
    const std::string stale_scan = "--progress none scan --station " + station.string() +
                                   " --steps 4 --stop-after 1 --calibration " + calibration.string();
    ASSERT_EQ(setenv("SOURCE_DATE_EPOCH", std::to_string(later).c_str(), 1), 0);
    r = scanstation(stale_scan + " -o " + (dir / "c").string());
    const Outcome accepted = scanstation(stale_scan + " --calibration-max-age 60 -o " + (dir / "d").string());
    unsetenv("SOURCE_DATE_EPOCH");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_THAT(r.err, testing::HasSubstr("is stale: its camera.date is 40.0 days old"));
    EXPECT_THAT(r.err, testing::HasSubstr("--calibration-max-age"));
    EXPECT_EQ(accepted.exit_code, 0) << accepted.err;

    // A part dated ahead of this machine's clock, and a camera part edited to
    // another image size than the station's (its fingerprint intact): the
    // first was accepted (no age), the second stopped the scan after a step.
    const long long earlier = static_cast<long long>(timegm(&made)) - 40 * 86400;
    ASSERT_EQ(setenv("SOURCE_DATE_EPOCH", std::to_string(earlier).c_str(), 1), 0);
    r = scanstation(stale_scan + " -o " + (dir / "f").string());
    unsetenv("SOURCE_DATE_EPOCH");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_THAT(r.err, testing::HasSubstr("days in the future"));
    json resized = json::parse(slurp(calibration));
    resized["camera"]["geometry"]["width"] = 1280;
    write_json(dir / "resized.json", resized);
    r = short_scan(station, "--calibration " + (dir / "resized.json").string(), dir / "h");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_THAT(r.err, testing::HasSubstr("resized.json: camera is 1280x480, the station's camera delivers 640x480"));
    EXPECT_FALSE(fs::exists(dir / "h" / "manifest.json"));

    // A calibration file that is not there.
    r = scanstation("scan --station " + station.string() + " --calibration nowhere.json -o " + (dir / "e").string());
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_THAT(r.err, testing::HasSubstr("nowhere.json does not exist"));
  }
}

}  // namespace
}  // namespace scanstation
