// `scanstation replay SESSION --calibration FILE`: a recorded session
// reprocessed with another calibration file instead of its recorded geometry.
// A file holding the simulator's true geometry gives the recorded points byte
// for byte; a perturbed one gives other points and the report names it; files
// for other devices, incomplete, stale ones and sessions that record no
// station fingerprint are refused as a scan refuses them.
#include "acquisition/station_calibration.h"
#include "cli_support.h"
#include "sim/simulated_turntable.h"
#include "test_support.h"

#include <nlohmann/json.hpp>

namespace scanstation {
namespace {

using nlohmann::json;
using test::Outcome;
using test::scanstation;
using test::ScratchFolder;
using test::slurp;
namespace fs = std::filesystem;

fs::path write_station(const ScratchFolder& dir, const std::string& name, int width, int height) {
  const fs::path file = dir / (name + ".toml");
  std::ofstream(file) << "name = \"bench\"\n[camera]\nbackend = \"sim\"\nwidth = " << width << "\nheight = " << height
                      << "\n[[laser]]\nbackend = \"sim\"\n[[laser]]\nbackend = \"sim\"\n[turntable]\nbackend = \"sim\"\n";
  return file;
}

// A calibration file holding the simulated rig's true geometry, dated `date`.
acquisition::StationCalibration truth_calibration(const fs::path& station, const std::string& date) {
  const drivers::StationDescription description = drivers::read_station(station);
  const sim::TurntableLaserRig rig = sim::station_rig(description);
  acquisition::StationCalibration c;
  c.created = c.updated = date;
  c.software_version = "test";
  c.station = acquisition::station_fingerprint(description);
  acquisition::CameraPart camera;
  camera.date = date;
  camera.camera = rig.camera;
  camera.posed = true;
  c.camera = camera;
  const std::vector<LaserPlane> planes = sim::light_planes(rig);
  for (std::size_t i = 0; i < planes.size(); ++i) {
    acquisition::LaserPart laser;
    laser.index = static_cast<int>(i);
    laser.date = date;
    laser.plane = planes[i];
    c.lasers.push_back(laser);
  }
  return c;
}

void write(const fs::path& file, const acquisition::StationCalibration& c) {
  acquisition::write_station_calibration(file, c, io::Overwrite::replace);
}

TEST(ReplayWithCalibration, TruthFileGivesTheRecordedPointsOthersDifferOrAreRefused) {
  ScratchFolder dir;
  const fs::path station = write_station(dir, "station", 320, 240), session = dir / "session";
  const Outcome scan = scanstation("--progress none scan --station " + station.string() +
                                   " --steps 8 --object sphere -o " + session.string());
  ASSERT_EQ(scan.exit_code, 0) << scan.err;
  const std::string recorded = slurp(session / "points.ply");
  const std::string now = acquisition::calibration_date();
  const auto replay = [&](const std::string& arguments, const fs::path& out) {
    return scanstation("--progress none replay " + session.string() + " -o " + out.string() + " " + arguments);
  };
  {
    SCOPED_TRACE("the simulator's truth as a calibration file: the recorded points, byte for byte");
    const fs::path truth = dir / "truth.json";
    write(truth, truth_calibration(station, now));
    const Outcome r = replay("--calibration " + truth.string(), dir / "a");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_THAT(r.out, testing::HasSubstr("geometry: " + truth.string()));
    EXPECT_EQ(slurp(dir / "a" / "points.ply"), recorded);
    const json report = json::parse(slurp(dir / "a" / "report.json"));
    EXPECT_EQ(report["geometry_source"], truth.string());
    EXPECT_FALSE(report["geometry"]["recorded"].get<bool>());
    EXPECT_EQ(report["geometry"]["calibration"]["file"], truth.string());
    // Without --calibration the recorded geometry, said so.
    const Outcome plain = replay("", dir / "p");
    ASSERT_EQ(plain.exit_code, 0) << plain.err;
    EXPECT_THAT(plain.out, testing::HasSubstr("geometry: as recorded: simulator truth"));
    EXPECT_TRUE(json::parse(slurp(dir / "p" / "report.json"))["geometry"]["recorded"].get<bool>());
  }
  {
    SCOPED_TRACE("a perturbed calibration: other points, the file named");
    acquisition::StationCalibration perturbed = truth_calibration(station, now);
    const double tilt = 0.5 * std::acos(-1.0) / 180.0;  // laser 0's plane turned by 0.5° about the vertical
    perturbed.lasers[0].plane.normal = turntable_rotation(tilt) * perturbed.lasers[0].plane.normal;
    const fs::path file = dir / "perturbed.json";
    write(file, perturbed);
    const Outcome r = replay("--calibration " + file.string(), dir / "b");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(slurp(dir / "b" / "points.ply"), recorded);
    const json report = json::parse(slurp(dir / "b" / "report.json"));
    EXPECT_EQ(report["geometry_source"], file.string());
    EXPECT_EQ(report["points"], json::parse(slurp(session / "report.json"))["points"]) << "the same stripes";
  }
  {
    SCOPED_TRACE("refusals");
    // Made for a 640×480 camera: the field and the session are named.
    const fs::path other = dir / "other.json";
    write(other, truth_calibration(write_station(dir, "big", 640, 480), now));
    Outcome r = replay("--calibration " + other.string(), dir / "c");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_THAT(r.err, testing::HasSubstr("replay of " + session.string()));
    EXPECT_THAT(r.err, testing::HasSubstr("camera.width: calibrated 640, station 320"));
    EXPECT_FALSE(fs::exists(dir / "c" / "points.ply"));

    // No laser planes.
    acquisition::StationCalibration incomplete = truth_calibration(station, now);
    incomplete.lasers.clear();
    write(dir / "incomplete.json", incomplete);
    r = replay("--calibration " + (dir / "incomplete.json").string(), dir / "d");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_THAT(r.err, testing::HasSubstr("has no plane for laser 0: run `scanstation calibrate laser`"));

    // Years old: stale unless accepted.
    const fs::path old = dir / "old.json";
    write(old, truth_calibration(station, "2020-01-01T00:00:00Z"));
    r = replay("--calibration " + old.string(), dir / "e");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_THAT(r.err, testing::HasSubstr(old.string() + " is stale: its"));
    EXPECT_THAT(r.err, testing::HasSubstr("`scanstation calibrate laser --force`"));
    r = replay("--calibration " + old.string() + " --calibration-max-age 0", dir / "f");
    EXPECT_EQ(r.exit_code, 0) << r.err;

    // Missing file; a session that records no station fingerprint.
    r = replay("--calibration " + (dir / "nowhere.json").string(), dir / "g");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_THAT(r.err, testing::HasSubstr("nowhere.json does not exist"));
    json manifest = json::parse(slurp(session / "manifest.json"));
    manifest["station"].erase("fingerprint");
    std::ofstream(session / "manifest.json") << manifest.dump(2);
    r = replay("--calibration " + (dir / "truth.json").string(), dir / "h");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_THAT(r.err, testing::HasSubstr("records no station.fingerprint"));
  }
}

}  // namespace
}  // namespace scanstation
