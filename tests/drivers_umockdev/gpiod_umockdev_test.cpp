// The real libgpiod 1.6 path of drivers/gpiod_lines.cpp (GpiodProvider,
// linked against Debian's libgpiod) against an emulated /dev/gpiochip0
// (umockdev_gpio_chip.h): chip lookup by name and /dev path (with libgpiod's
// sysfs check of the character device), lines by offset and by name on a
// chip, consumer labels, outputs requested at their safe level, active-low,
// EBUSY naming the holder, values written and read through line handles, and
// release on close. The levels land in a simulated chip, so the stepper pulse
// train can be checked on the real GPIO path too.
#include "drivers/device_error.h"
#include "drivers/gpiod_lines.h"
#include "drivers/laser.h"
#include "drivers/station_description.h"
#include "drivers/stepper_turntable.h"
#include "drivers/trapezoid_ramp.h"
#include "sim/devices/open_station.h"
#include "sim/devices/sim_gpio_chip.h"
#include "sim/devices/sim_stepper_motor.h"
#include "sim/devices/virtual_clock.h"
#include "test_support.h"
#include "umockdev_gpio_chip.h"

#include <algorithm>

namespace scanstation::drivers {
namespace {

using namespace std::chrono_literals;
using test::EmulatedGpioChip;

class GpiodUmockdev : public testing::Test {
 protected:
  void SetUp() override {
    if (!test::umockdev_preloaded()) GTEST_SKIP() << test::kNotPreloaded;
    chip_ = std::make_unique<EmulatedGpioChip>(lines_, "gpiochip0");
  }
  sim::VirtualClock clock_;
  sim::SimGpioChip lines_{"pinctrl-sim", {"LASER0", "STEP", "DIR", "EN", "HOME"}, clock_};
  std::unique_ptr<EmulatedGpioChip> chip_;
  GpiodProvider gpio_;
};

TEST_F(GpiodUmockdev, OutputsAreRequestedAtTheirSafeLevelWithTheConsumerLabel) {
  lines_.drive(0, true);  // the pin floats high before the program starts
  {
    auto laser = gpio_.request_output({"gpiochip0", 0u, ""}, "scanstation", false);
    EXPECT_FALSE(lines_.level(0)) << "driven low by the request itself";
    EXPECT_EQ(lines_.consumer(0), "scanstation");
    EXPECT_EQ(laser->describe(), "gpiochip0:0");
    laser->set(true);
    EXPECT_TRUE(lines_.level(0));
    EXPECT_TRUE(laser->value()) << "read back through GPIOHANDLE_GET_LINE_VALUES";
  }
  EXPECT_EQ(chip_->open_requests(), 0) << "closing the handle descriptor released the request";
  auto again = gpio_.request_output({"gpiochip0", 0u, ""}, "scanstation", false);
  EXPECT_EQ(lines_.consumer(0), "scanstation") << "the line was free again";
  EXPECT_FALSE(lines_.level(0)) << "requested again at its safe level";
  const auto log = chip_->ioctl_log();
  for (const char* ioctl : {"GET_CHIPINFO", "GET_LINEINFO", "GET_LINEHANDLE", "SET_LINE_VALUES", "GET_LINE_VALUES"})
    EXPECT_NE(std::find(log.begin(), log.end(), ioctl), log.end()) << ioctl;
}

TEST_F(GpiodUmockdev, LinesByNameOnAChipByPathAndActiveLow) {
  auto enable = gpio_.request_output({"/dev/gpiochip0", {}, "EN", true}, "scanstation", false);
  EXPECT_EQ(enable->describe(), "gpiochip0:3 (EN)");
  EXPECT_TRUE(lines_.level(3)) << "active-low: logical off is a high pin";
  enable->set(true);
  EXPECT_FALSE(lines_.level(3));
  auto home = gpio_.request_input({"gpiochip0", {}, "HOME"}, "scanstation");
  lines_.drive(4, true);
  EXPECT_TRUE(home->value());
  lines_.drive(4, false);
  EXPECT_FALSE(home->value());
}

TEST_F(GpiodUmockdev, BusyLineAndMissingLinesAreClearErrors) {
  auto held = gpio_.request_output({"gpiochip0", 1u, ""}, "other-program", false);
  test::expect_error<DeviceError>([&] { gpio_.request_output({"gpiochip0", 1u, ""}, "scanstation", false); },
                                  {"gpiochip0:1", "busy", "held by other-program"});
  test::expect_error<DeviceError>([&] { gpio_.request_output({"gpiochip0", 9u, ""}, "scanstation", false); },
                                  {"has no line 9"});
  test::expect_error<DeviceError>([&] { gpio_.request_output({"gpiochip0", {}, "LASER7"}, "scanstation", false); },
                                  {"has no line named 'LASER7'"});
  test::expect_error<DeviceError>([&] { gpio_.request_output({"gpiochip5", 0u, ""}, "scanstation", false); },
                                  {"GPIO chip 'gpiochip5' cannot be opened"});
}

TEST_F(GpiodUmockdev, StepperPulseTrainAndHomingThroughLibgpiod) {
  sim::SimStepperMotor motor(lines_, {3200, 1000, 9});  // the table stands 112.5° past its switch
  StepperConfig config;
  config.max_speed_deg_s = 90;
  config.acceleration_deg_s2 = 180;
  {
    StepperLines lines{gpio_.request_output({"gpiochip0", {}, "STEP"}, "scanstation", false),
                       gpio_.request_output({"gpiochip0", {}, "DIR"}, "scanstation", false),
                       gpio_.request_output({"gpiochip0", {}, "EN"}, "scanstation", false),
                       gpio_.request_input({"gpiochip0", {}, "HOME"}, "scanstation")};
    StepperTurntable table(std::move(lines), clock_, config);
    table.home();
    EXPECT_EQ(motor.position() % 3200, 0) << "homed on the switch";
    table.rotate_by(-45.0);
    EXPECT_EQ(motor.position() % 3200, -400);
    EXPECT_EQ(motor.lost_steps(), 0);
  }
  EXPECT_FALSE(lines_.level(3)) << "motor disabled when the turntable went away";
  EXPECT_FALSE(lines_.level(1));
  // The last 400 rising STEP edges follow the trapezoid of a 400-step move.
  std::vector<Timestamp> edges;
  for (const auto& t : lines_.transitions(1))
    if (t.level) edges.push_back(t.time);
  ASSERT_GE(edges.size(), 400u);
  const double per_degree = 3200 / 360.0;
  const auto ideal = trapezoid_step_times(400, config.max_speed_deg_s * per_degree, config.acceleration_deg_s2 * per_degree);
  const std::vector<Timestamp> move(edges.end() - 400, edges.end());
  for (std::size_t i = 1; i < move.size(); ++i)
    EXPECT_NEAR(to_seconds(move[i] - move[0]), ideal[i] - ideal[0], 1e-6) << "step " << i;
}

TEST_F(GpiodUmockdev, GpioStationOpensThroughLibgpiodAndEndsSafe) {
  StationDescription d;
  d.lasers = {LaserRole{}};
  d.lasers[0].backend = "gpio";
  d.lasers[0].line = {"gpiochip0", {}, "LASER0"};
  d.turntable.backend = "gpio";
  d.turntable.step = {"gpiochip0", 1u, ""};
  d.turntable.direction = {"gpiochip0", 2u, ""};
  d.turntable.enable = {"gpiochip0", {}, "EN", true};
  d.turntable.home = LineAddress{"gpiochip0", {}, "HOME"};
  {
    sim::GuardedStation station(d, sim::laser_role | sim::turntable_role);
    station->lasers[0]->set(true);
    EXPECT_TRUE(lines_.level(0));
    EXPECT_EQ(lines_.consumer(4), "scanstation") << "the home switch input is held too";
    station->turntable->rotate_by(1.0);
    EXPECT_FALSE(lines_.level(3)) << "low-active EN pin driven low: motor on";
  }
  EXPECT_FALSE(lines_.level(0)) << "laser off at the end";
  EXPECT_TRUE(lines_.level(3)) << "low-active EN pin high: motor off";
}

}  // namespace
}  // namespace scanstation::drivers
