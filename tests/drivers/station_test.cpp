// Station description files: the examples in stations/ parse, bad values are
// refused with file, line and field; a simulated station opens, scans a few
// laser on/off pairs with settled frames, and ends in its safe state.
#include "drivers/device_error.h"
#include "drivers/frame_gate.h"
#include "drivers/station_description.h"
#include "sim/devices/open_station.h"
#include "test_support.h"

#include <fstream>

namespace scanstation::drivers {
namespace {

using namespace std::chrono_literals;

std::filesystem::path stations() { return std::filesystem::path(SCANSTATION_SOURCE_DIR) / "stations"; }

TEST(StationDescription, ExampleFilesParse) {
  const StationDescription real = read_station(stations() / "example-real.toml");
  EXPECT_EQ(real.name, "bench-1");
  EXPECT_EQ(real.camera.backend, "v4l2");
  EXPECT_EQ(real.camera.format, (CameraFormat{PixelFormat::grey, {1280, 720}, 4}));
  ASSERT_EQ(real.camera.controls.size(), 3u);
  EXPECT_EQ(real.camera.controls[0], (std::pair<std::string, std::int64_t>{"auto_exposure", 1}));
  ASSERT_EQ(real.lasers.size(), 2u);
  EXPECT_EQ(real.lasers[0].line.offset, 17u);
  EXPECT_EQ(real.lasers[1].line.name, "GPIO27");
  EXPECT_TRUE(real.turntable.enable.active_low);
  EXPECT_EQ(real.turntable.home->offset, 25u);
  EXPECT_DOUBLE_EQ(real.turntable.stepper.steps_per_rev(), 12800.0);
  EXPECT_EQ(real.usb.vendor, 0x1209);
  const StationDescription sim = real.simulated();
  EXPECT_EQ(sim.camera.backend, "sim");
  EXPECT_EQ(sim.turntable.backend, "sim");
  EXPECT_EQ(read_station(stations() / "sim.toml").lasers.size(), 2u);
}

TEST(StationDescription, MistakesNameFileLineAndField) {
  test::ScratchFolder folder;
  auto check = [&](const std::string& text, std::initializer_list<std::string> parts) {
    const auto file = folder / "station.toml";
    std::ofstream(file) << text;
    test::expect_error<FormatError>([&] { read_station(file); }, parts);
  };
  check("[camera]\nwidth = -3\n", {"station.toml:2", "camera.width", "integer in [16, 16384]"});
  check("[camera]\nbackend = \"usb\"\n", {":2", "camera.backend", "\"sim\", \"v4l2\""});
  check("[camera]\nformat = \"RGB3\"\n", {"camera.format", "GREY, Y16, YUYV or MJPG"});
  check("[turntable]\nmicrostep = 16\n", {":2", "turntable.microstep: unknown key"});
  check("[turntable]\nbackend = \"gpio\"\nstep = 1\ndir = 2\n", {"turntable.enable", "step, dir and enable"});
  check("[[laser]]\nbackend = \"gpio\"\nline = 1.5\n", {":3", "laser[0].line", "offset"});
  check("[camera\n", {"station.toml:1"});
  // nan fails every comparison: it passed the range checks and reached the
  // simulator (an assertion in the ray tracer, exit 134, for the table angle).
  check("[sim]\ntable_angle_deg = nan\n", {"station.toml:2", "sim.table_angle_deg", "number in [-1000000, 1000000]"});
  check("[turntable]\ngear_ratio = nan\n", {":2", "turntable.gear_ratio"});
  check("[[laser]]\nsettle_ms = nan\n", {":2", "laser[0].settle_ms"});
  check("[turntable]\nfull_steps_per_rev = 1\nmicrosteps = 1\n", {"1 steps per turn, at least 16"});
  check("calibration = \"\"\n", {"station.toml:1", "calibration: expected a file name"});
  test::expect_error<InvalidInput>([&] { read_station(folder / "missing.toml"); }, {"does not exist"});
  // A folder was read as an empty file: the default station, under its name.
  test::expect_error<InvalidInput>([&] { read_station(folder.path()); }, {"is a folder, expected a file"});
}

TEST(OpenStation, SimulatedStationScansSettledPairsAndEndsSafe) {
  StationDescription d = read_station(stations() / "sim.toml");
  auto station = sim::open_station(d, sim::camera_role | sim::laser_role | sim::turntable_role);
  ASSERT_TRUE(station->sim_chip);
  station->camera->start();
  for (int step = 0; step < 8; ++step) {
    const Timestamp moved = station->turntable->rotate_by(45.0);
    for (const bool on : {true, false}) {
      const Timestamp settled = std::max(moved, station->lasers[0]->set(on));
      const SettledFrame frame = grab_settled(*station->camera, *station->clock, settled, 1000ms);
      EXPECT_GT(frame.frame.exposure_start, settled);
      EXPECT_EQ(station->sim_chip->level_at(0, frame.frame.exposure_start), on);
      EXPECT_FALSE(frame.frame.image.empty());
    }
  }
  // A frame the caller does not want is not rendered: it comes without an
  // image, stamped and numbered as any other, and the next one has its image.
  const Frame skipped = station->camera->grab_if(1000ms, [](const Frame&) { return false; });
  EXPECT_TRUE(skipped.image.empty());
  const Frame next = station->camera->grab(1000ms);
  EXPECT_FALSE(next.image.empty());
  EXPECT_EQ(next.sequence, skipped.sequence + 1);
  EXPECT_GT(next.exposure_start, skipped.exposure_start);
  EXPECT_NEAR(station->turntable->angle(), 360.0, 1e-9);
  station->lasers[0]->set(true);
  station.reset();  // normal end
}

TEST(StationDescription, StereoStationNamesASecondCameraAndAProjector) {
  const StationDescription d = read_station(stations() / "sim-stereo.toml");
  ASSERT_TRUE(d.right_camera && d.projector);
  EXPECT_EQ(d.right_camera->format.size.width, 640);
  EXPECT_EQ(d.projector->backend, "sim");
  EXPECT_FALSE(read_station(stations() / "sim.toml").right_camera) << "a laser station has none";
  test::ScratchFolder folder;
  std::ofstream(folder / "s.toml") << "[projector]\nbackend = \"gpio\"\n";
  test::expect_error<FormatError>([&] { read_station(folder / "s.toml"); }, {"s.toml:1", "projector.line"});
  std::ofstream(folder / "s.toml") << "[right_camera]\nwidth = 320\nlens = 4\n";
  test::expect_error<FormatError>([&] { read_station(folder / "s.toml"); }, {":3", "right_camera.lens: unknown key"});
  std::ofstream(folder / "s.toml") << "[projector]\nbackend = \"gpio\"\nline = 5\n";
  EXPECT_EQ(read_station(folder / "s.toml").simulated().projector->backend, "sim");
}

// The stereo roles are devices like the others: the right camera streams,
// the projector is a line of the simulated chip switched like a laser, and
// both reach their safe state.
TEST(OpenStation, StereoRolesOpenAsDevices) {
  const StationDescription d = read_station(stations() / "sim-stereo.toml");
  auto station = sim::open_station(d, sim::camera_role | sim::right_camera_role | sim::projector_role |
                                          sim::turntable_role);
  ASSERT_TRUE(station->right_camera && station->projector);
  const unsigned line = station->sim_chip->offset_of("PROJECTOR");
  station->right_camera->start();
  const Timestamp lit = station->projector->set(true);
  const SettledFrame frame = grab_settled(*station->right_camera, *station->clock, lit, 1000ms);
  EXPECT_TRUE(station->sim_chip->level_at(line, frame.frame.exposure_start));
  EXPECT_EQ(frame.frame.image.cols, 640);
  station->make_safe();
  EXPECT_FALSE(station->projector->is_on());
  test::expect_error<DeviceError>([&] { station->projector->set(true); }, {"held off by the safe state"});
  StationDescription no_right = d;
  no_right.right_camera.reset();
  test::expect_error<InvalidInput>([&] { sim::open_station(no_right, sim::right_camera_role); },
                                   {"sim-stereo.toml", "[right_camera]"});
}

TEST(OpenStation, SimulatedTableHomesOnItsSwitch) {
  StationDescription d;
  d.sim_table_angle_deg = 200.0;  // where the table happens to stand at power-up
  auto station = sim::open_station(d, sim::turntable_role);
  ASSERT_TRUE(station->sim_motor);
  station->turntable->rotate_by(30.0);
  EXPECT_EQ(station->sim_motor->position(), 1778 + 267) << "start 200° plus 30°, each rounded to microsteps";
  station->turntable->home();
  EXPECT_EQ(station->sim_motor->position() % 3200, 0) << "physically at the switch";
  EXPECT_DOUBLE_EQ(station->turntable->angle(), 0.0);
  station->make_safe();
  test::expect_error<DeviceError>([&] { station->turntable->rotate_by(1.0); }, {"stopped by the safe state"});
}

TEST(OpenStation, GuardedStationEndsSafe) {
  test::ScratchFolder folder;
  StationDescription d;
  d.sim_state_file = folder / "lines";  // LASER0, STEP, DIR, EN, HOME
  {
    sim::GuardedStation station(d, sim::laser_role | sim::turntable_role);
    station->lasers[0]->set(true);
    station->turntable->rotate_by(10.0);
    EXPECT_EQ(sim::SimGpioChip::read_state_file(d.sim_state_file), (std::vector<bool>{true, false, true, true, false}));
    EXPECT_THROW(sim::GuardedStation(d, sim::laser_role), InvalidInput) << "one guard per process";
  }
  EXPECT_EQ(sim::SimGpioChip::read_state_file(d.sim_state_file), (std::vector<bool>{false, false, true, false, false}));
}

TEST(OpenStation, UsbRolesOfASimulatedStationSpeakTheProtocol) {
  StationDescription d;
  d.lasers = {LaserRole{"usb", {}, 1, 2ms}};
  d.turntable.backend = "usb";
  d.usb_simulated = true;
  auto station = sim::open_station(d, sim::laser_role | sim::turntable_role);
  station->lasers[0]->set(true);
  EXPECT_TRUE(station->sim_board->laser(1));
  station->turntable->rotate_by(-30.0);
  EXPECT_EQ(station->sim_board->position(), -267);
  station->make_safe();
  EXPECT_FALSE(station->sim_board->laser(1));
  EXPECT_FALSE(station->sim_board->motor_enabled());
}

}  // namespace
}  // namespace scanstation::drivers
