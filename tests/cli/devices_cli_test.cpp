// End-to-end tests of the device commands: devices, capture, turntable and
// laser on simulated stations, and the safe state of a killed `laser on`.
#include "cli_support.h"
#include "test_support.h"

#include <chrono>
#include <csignal>
#include <nlohmann/json.hpp>
#include <spawn.h>
#include <thread>

extern char** environ;

namespace scanstation {
namespace {

using test::Outcome;
using test::ScratchFolder;
using test::scanstation;
using test::slurp;

const std::string kStations = std::string(SCANSTATION_SOURCE_DIR) + "/stations/";

TEST(DevicesCli, ListsWhatIsPresentAndSaysSoWhenNothingIs) {
  const Outcome r = scanstation("devices");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const bool hardware = std::filesystem::exists("/dev/video0") || std::filesystem::exists("/dev/gpiochip0");
  if (!hardware) {
    EXPECT_THAT(r.out, testing::HasSubstr("no cameras, GPIO chips or USB controllers found"));
  }
}

TEST(DevicesCli, SimulatedStationListsCameraChipAndBoard) {
  ScratchFolder dir;
  ScratchFolder stations;
  std::ofstream(stations / "usb.toml") << "[[laser]]\nbackend = \"usb\"\nindex = 1\n[turntable]\nbackend = \"usb\"\n";
  const Outcome r = scanstation("devices --backend sim --station " + (stations / "usb.toml").string() + " --report " +
                                (dir / "r.json").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto report = nlohmann::json::parse(slurp(dir / "r.json"));
  ASSERT_EQ(report["cameras"].size(), 1u);
  EXPECT_EQ(report["cameras"][0]["formats"].size(), 4u);
  EXPECT_THAT(r.out, testing::HasSubstr("firmware 1.2.0"));
  const Outcome gpio = scanstation("devices --backend sim --station " + kStations + "sim.toml");
  EXPECT_THAT(gpio.out, testing::HasSubstr("LASER1"));
  EXPECT_THAT(gpio.out, testing::HasSubstr("STEP"));
}

// Width and height from a PNG's IHDR chunk.
std::pair<int, int> png_size(const std::string& png) {
  auto be32 = [&](std::size_t at) {
    return (std::uint8_t(png[at]) << 24) | (std::uint8_t(png[at + 1]) << 16) | (std::uint8_t(png[at + 2]) << 8) |
           std::uint8_t(png[at + 3]);
  };
  return {int(be32(16)), int(be32(20))};
}

TEST(DevicesCli, CaptureWritesPngFramesOfTheStationFormat) {
  ScratchFolder dir;
  const Outcome r = scanstation("capture --backend sim --station " + kStations + "example-real.toml -n 3 -o " +
                                (dir / "frames").string() + " --laser 0 --report " + (dir / "r.json").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* name : {"frame_0000.png", "frame_0001.png", "frame_0002.png"})
    EXPECT_EQ(png_size(slurp(dir / "frames" / name)), (std::pair{1280, 720})) << name;
  const auto report = nlohmann::json::parse(slurp(dir / "r.json"));
  const auto& frames = report["frames"];
  ASSERT_EQ(frames.size(), 3u);
  EXPECT_LT(frames[0]["sequence"].get<int>(), frames[2]["sequence"].get<int>());
  EXPECT_EQ(scanstation("capture -n 1 -o " + (dir / "frames").string()).exit_code, 1) << "existing frames kept";
  EXPECT_EQ(scanstation("capture -n 1 -o " + (dir / "x").string() + " --laser 3").exit_code, 1);
}

TEST(DevicesCli, TurntableAndLaserOnTheSimulatedStation) {
  ScratchFolder dir;
  Outcome r = scanstation("turntable --rotate -90 --backend sim --report " + (dir / "t.json").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_DOUBLE_EQ(nlohmann::json::parse(slurp(dir / "t.json"))["angle_deg"].get<double>(), -90.0);
  EXPECT_EQ(scanstation("turntable --rotate 10 --to 20").exit_code, 1);
  // The simulated table stands at 123° and closes its home switch at 0°.
  std::ofstream(dir / "home.toml") << "[sim]\ntable_angle_deg = 123.0\n";
  r = scanstation("turntable --home --station " + (dir / "home.toml").string() + " --report " + (dir / "h.json").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_DOUBLE_EQ(nlohmann::json::parse(slurp(dir / "h.json"))["angle_deg"].get<double>(), 0.0);
  EXPECT_GT(nlohmann::json::parse(slurp(dir / "h.json"))["motion_s"].get<double>(), 123.0 / 10.0) << "sought at 10°/s";
  r = scanstation("laser 1 on --hold 0.05 --station " + kStations + "sim.toml");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, testing::HasSubstr("laser 1 (simchip0:1 (LASER1)) on"));
  r = scanstation("laser 2 off --station " + kStations + "sim.toml");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, testing::HasSubstr("the station has 2 laser(s)"));
  // An empty number was laser 0.
  r = scanstation("laser \"\" off --station " + kStations + "sim.toml");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, testing::HasSubstr("index: expected a whole number in [0, 63], got ''"));
}

TEST(DevicesCli, BadStationFileNamesLineAndField) {
  ScratchFolder dir;
  std::ofstream(dir / "bad.toml") << "[turntable]\nmicrosteps = 1000\n";
  const Outcome r = scanstation("turntable --rotate 1 --station " + (dir / "bad.toml").string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, testing::HasSubstr("bad.toml:2"));
  EXPECT_THAT(r.err, testing::HasSubstr("turntable.microsteps"));
}

TEST(DevicesCli, SigtermToLaserOnLeavesTheLaserOff) {
  ScratchFolder dir;
  const auto lines = dir / "lines";
  std::ofstream(dir / "station.toml") << "[[laser]]\nbackend = \"sim\"\n[sim]\nstate_file = \"" << lines.string()
                                      << "\"\n";
  const std::string binary = SCANSTATION_BINARY, station = (dir / "station.toml").string();
  const char* argv[] = {binary.c_str(), "-q", "laser", "0", "on", "--station", station.c_str(), nullptr};
  pid_t child = 0;
  ASSERT_EQ(posix_spawn(&child, binary.c_str(), nullptr, nullptr, const_cast<char**>(argv), environ), 0);
  // Wait until the child has switched the laser on, or has ended without.
  int status = 0;
  bool ended = false;
  while (slurp(lines).rfind('1', 0) != 0 && !(ended = waitpid(child, &status, WNOHANG) == child))
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  const std::string before = slurp(lines);
  ASSERT_FALSE(ended) << "the child ended before the laser came on (exit status " << status << ")";
  kill(child, SIGTERM);
  waitpid(child, &status, 0);
  ASSERT_EQ(before.substr(0, 1), "1") << "the laser came on (levels LASER0, STEP, DIR, EN)";
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM);
  EXPECT_EQ(slurp(lines).substr(0, 1), "0");
}

}  // namespace
}  // namespace scanstation
