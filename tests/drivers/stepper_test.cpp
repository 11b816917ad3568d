// Stepper turntable on simulated GPIO lines: the pulse train of a move (count,
// direction, trapezoidal timing), absolute angle tracking, home switch.
#include "drivers/device_error.h"
#include "drivers/stepper_turntable.h"
#include "drivers/trapezoid_ramp.h"
#include "sim/devices/sim_gpio_chip.h"
#include "sim/devices/sim_stepper_motor.h"
#include "sim/devices/virtual_clock.h"
#include "test_support.h"

#include <cmath>

namespace scanstation::drivers {
namespace {

using sim::SimGpioChip;
using sim::Transition;
using sim::VirtualClock;

struct Rig {
  VirtualClock clock;
  SimGpioChip chip{"simchip0", {"STEP", "DIR", "EN", "HOME"}, clock};
  StepperConfig config;
  std::unique_ptr<StepperTurntable> table;

  explicit Rig(StepperConfig c = {}, bool with_home = false) : config(c) {
    StepperLines lines;
    lines.step = chip.request_output({"", {}, "STEP"}, "test", false);
    lines.direction = chip.request_output({"", {}, "DIR"}, "test", false);
    lines.enable = chip.request_output({"", {}, "EN"}, "test", false);
    if (with_home) lines.home = chip.request_input({"", {}, "HOME"}, "test");
    table = std::make_unique<StepperTurntable>(std::move(lines), clock, config);
  }
  std::vector<Timestamp> rising_edges() const {
    std::vector<Timestamp> edges;
    for (const Transition& t : chip.transitions(0))
      if (t.level) edges.push_back(t.time);
    return edges;
  }
};

TEST(TrapezoidRamp, ReachesTopSpeedAndIsSymmetric) {
  const double v = 1000, a = 4000;
  const auto times = trapezoid_step_times(2000, v, a);
  ASSERT_EQ(times.size(), 2000u);
  EXPECT_TRUE(std::is_sorted(times.begin(), times.end()));
  EXPECT_NEAR(times.back(), trapezoid_duration(2000, v, a), 1e-12);
  // Ramp of v²/2a = 125 steps: the cruise interval is exactly 1/v.
  EXPECT_NEAR(times[1000] - times[999], 1.0 / v, 1e-9);
  // No interval is shorter than the top speed allows.
  for (std::size_t i = 1; i < times.size(); ++i) EXPECT_GE(times[i] - times[i - 1], 1.0 / v - 1e-9);
  // Deceleration mirrors acceleration.
  for (std::size_t i = 1; i < 125; ++i)
    EXPECT_NEAR(times[i] - times[i - 1], times[1999 - i] - times[1998 - i], 1e-9);
}

TEST(TrapezoidRamp, ShortMoveIsATriangleBelowTopSpeed) {
  const auto times = trapezoid_step_times(20, 1000, 4000);
  ASSERT_EQ(times.size(), 20u);
  for (std::size_t i = 1; i < times.size(); ++i) EXPECT_GT(times[i] - times[i - 1], 1.0 / 1000);
  EXPECT_TRUE(trapezoid_step_times(0, 1000, 4000).empty());
  EXPECT_THROW(trapezoid_step_times(10, 0, 4000), InvalidInput);
}

TEST(StepperTurntable, PulseTrainHasCountDirectionAndRamp) {
  StepperConfig config;
  config.max_speed_deg_s = 90;
  config.acceleration_deg_s2 = 180;
  Rig rig(config);
  const Timestamp before = rig.clock.now();
  const Timestamp settled = rig.table->rotate_by(-90.0);
  const double per_degree = config.steps_per_rev() / 360.0;  // 8.888…
  const auto edges = rig.rising_edges();
  ASSERT_EQ(edges.size(), 800u);  // 90° of 3200 microsteps per turn
  EXPECT_FALSE(rig.chip.level(1)) << "negative rotation drives DIR low";
  EXPECT_TRUE(rig.chip.level(2)) << "motor stays enabled between moves";
  EXPECT_EQ(settled, rig.clock.now() + config.settle);
  EXPECT_DOUBLE_EQ(rig.table->angle(), -90.0);
  // DIR is set and the driver enabled before the first step edge.
  const auto dir = rig.chip.transitions(2);
  ASSERT_FALSE(dir.empty());
  EXPECT_GE(edges.front() - dir.back().time, config.enable_delay);
  // Every edge within 1 µs of the ideal trapezoid, measured from the first edge.
  const auto ideal = trapezoid_step_times(800, config.max_speed_deg_s * per_degree,
                                          config.acceleration_deg_s2 * per_degree);
  const Timestamp origin = edges.front() - seconds(ideal.front());
  for (std::size_t i = 0; i < edges.size(); ++i)
    EXPECT_NEAR(to_seconds(edges[i] - origin), ideal[i], 1e-6) << "step " << i;
  // Instantaneous speed never exceeds the limit by more than 1%.
  for (std::size_t i = 1; i < edges.size(); ++i)
    EXPECT_LE(1.0 / to_seconds(edges[i] - edges[i - 1]), 1.01 * config.max_speed_deg_s * per_degree);
  EXPECT_GT(edges.front(), before);
}

TEST(StepperTurntable, AbsoluteAngleDoesNotDriftOverManySmallMoves) {
  Rig rig;
  for (int i = 0; i < 360; ++i) rig.table->rotate_by(1.0 / 3.0);  // 1/3° is not a whole number of steps
  EXPECT_NEAR(rig.table->angle(), 120.0, 360.0 / 3200);
  EXPECT_EQ(rig.table->position(), std::llround(120.0 * 3200 / 360));
  rig.table->rotate_to(-10.0);  // shorter way: back by 130°
  EXPECT_NEAR(rig.table->angle(), -10.0, 360.0 / 3200);
  EXPECT_NEAR(shortest_rotation(350, 10), 20.0, 1e-12);
  EXPECT_NEAR(shortest_rotation(10, 190), 180.0, 1e-12);
}

TEST(StepperTurntable, HomesOnTheSwitchAndDisablesOnDestruction) {
  Rig rig({}, true);
  rig.table->rotate_by(30.0);
  // The switch closes when the table is back at 7 steps past 0.
  std::int64_t steps_back = 0;
  rig.chip.on_transition([&](const Transition& t) {
    if (t.line == 0 && t.level && !rig.chip.level(1) && ++steps_back == 260) rig.chip.drive(3, true);
  });
  rig.table->home();
  EXPECT_EQ(steps_back, 260);
  EXPECT_DOUBLE_EQ(rig.table->angle(), 0.0);
  rig.table.reset();
  EXPECT_FALSE(rig.chip.level(2)) << "enable released";
  EXPECT_FALSE(rig.chip.level(0));
}

TEST(StepperTurntable, HomeWithoutSwitchFailsClearly) {
  Rig rig;
  test::expect_error<DeviceError>([&] { rig.table->home(); }, {"no home switch"});
  StepperConfig config;
  config.home_overtravel_deg = 5.0;
  Rig homeless(config, true);  // a switch that never closes
  homeless.table->rotate_by(90.0);
  test::expect_error<DeviceError>([&] { homeless.table->home(); },
                                  {"home switch simchip0:3 (HOME)", "within 365.0° (3245 steps)", "wiring"});
  // The search is bounded: exactly the maximum travel backwards, then stopped.
  EXPECT_EQ(homeless.table->position(), 800 - 3245);
  Rig stuck({}, true);
  stuck.chip.drive(3, true);  // closed and never opening
  test::expect_error<DeviceError>([&] { stuck.table->home(); }, {"stays active", "stuck closed"});
}

// The simulated table (sim/devices/sim_stepper_motor.h) closes HOME at its
// physical angle 0; homing from anywhere lands exactly there.
TEST(StepperTurntable, HomesOnTheSimulatedTableSwitchFromAnyAngle) {
  for (const double start_deg : {123.4, 0.0, -5.0, 359.9, 720.0 + 17.0}) {
    VirtualClock clock;
    SimGpioChip chip{"simchip0", {"STEP", "DIR", "EN", "HOME"}, clock};
    const std::int64_t n = 3200;
    sim::SimStepperMotor motor(chip, {n, std::llround(start_deg / 360.0 * n), 9});
    StepperLines lines{chip.request_output({"", {}, "STEP"}, "test", false),
                       chip.request_output({"", {}, "DIR"}, "test", false),
                       chip.request_output({"", {}, "EN"}, "test", false), chip.request_input({"", {}, "HOME"}, "test")};
    StepperTurntable table(std::move(lines), clock, {});
    table.home();
    EXPECT_EQ(((motor.position() % n) + n) % n, 0) << "started at " << start_deg << "°";
    EXPECT_DOUBLE_EQ(table.angle(), 0.0);
    EXPECT_TRUE(chip.level(3)) << "at home the switch is closed";
    table.rotate_by(90.0);
    EXPECT_EQ(((motor.position() % n) + n) % n, 800) << "angles count from the switch";
    EXPECT_FALSE(chip.level(3));
    EXPECT_EQ(motor.lost_steps(), 0);
  }
}

TEST(SimStepperMotor, StepsWhileTheDriverIsDisabledAreLost) {
  VirtualClock clock;
  SimGpioChip chip{"simchip0", {"STEP", "DIR", "EN"}, clock};
  sim::SimStepperMotor motor(chip, {3200, 0, 9});
  auto step = chip.request_output({"", {}, "STEP"}, "test", false);
  auto dir = chip.request_output({"", {}, "DIR"}, "test", true);
  auto enable = chip.request_output({"", {}, "EN"}, "test", false);
  for (int i = 0; i < 3; ++i) step->set(true), step->set(false);
  enable->set(true);
  for (int i = 0; i < 5; ++i) step->set(true), step->set(false);
  EXPECT_EQ(motor.position(), 5);
  EXPECT_EQ(motor.lost_steps(), 3);
}

}  // namespace
}  // namespace scanstation::drivers
