// Safe state: lasers off and the motor disabled when the program ends by an
// exception or is killed with SIGTERM/SIGINT. The signal tests fork a child
// that holds a simulated GPIO chip mirrored into a state file, kill it, and
// read the levels the child left behind.
#include "core/errors.h"
#include "drivers/laser.h"
#include "drivers/safe_state.h"
#include "drivers/stepper_turntable.h"
#include "sim/devices/sim_gpio_chip.h"
#include "sim/devices/virtual_clock.h"
#include "test_support.h"

#include <csignal>
#include <sys/wait.h>
#include <unistd.h>

namespace scanstation::drivers {
namespace {

using namespace std::chrono_literals;

// Laser on line 0, stepper STEP/DIR/EN on 1..3.
struct Station {
  sim::VirtualClock clock;
  sim::SimGpioChip chip;
  Laser laser;
  StepperTurntable table;

  explicit Station(const std::filesystem::path& state_file = {})
      : chip("simchip0", {"LASER0", "STEP", "DIR", "EN"}, clock, state_file),
        laser(chip.request_output({"", 0u, ""}, "test", false), clock, 1ms),
        table(StepperLines{chip.request_output({"", 1u, ""}, "test", false),
                           chip.request_output({"", 2u, ""}, "test", false),
                           chip.request_output({"", 3u, ""}, "test", false), nullptr},
              clock, {}) {}
};

TEST(SafeState, ExceptionUnwindingSwitchesEverythingOff) {
  sim::VirtualClock clock;
  test::ScratchFolder folder;
  const auto file = folder / "lines";
  try {
    Station station(file);
    station.laser.set(true);
    station.table.rotate_by(5.0);
    ASSERT_EQ(sim::SimGpioChip::read_state_file(file), (std::vector<bool>{true, false, true, true}));
    throw std::runtime_error("scan failed");
  } catch (const std::runtime_error&) {
  }
  EXPECT_EQ(sim::SimGpioChip::read_state_file(file), (std::vector<bool>{false, false, true, false}))
      << "laser and enable off; DIR may stay as it was";
}

TEST(SafeState, GuardRunsActionsInReverseOnceDestroyed) {
  std::vector<std::string> order;
  {
    SafeStateGuard guard;
    guard.add("first", [&] { order.push_back("first"); });
    guard.add("failing", [] { throw std::runtime_error("device gone"); });
    guard.add("last", [&] { order.push_back("last"); });
    EXPECT_THROW(SafeStateGuard{}, InvalidInput) << "one guard per process";
  }
  EXPECT_EQ(order, (std::vector<std::string>{"last", "first"})) << "a failing action does not stop the others";
}

// Forks a child that switches the laser on, enables the motor, reports ready
// through a pipe and waits to be killed. Returns the child's levels after
// `signal_number` ended it, and how it ended.
std::pair<std::vector<bool>, int> kill_child_station(int signal_number, bool guarded) {
  test::ScratchFolder folder;
  const auto file = folder / "lines";
  int ready[2];
  if (pipe(ready) != 0) throw std::runtime_error("pipe");
  const pid_t child = fork();
  if (child == 0) {
    close(ready[0]);
    std::optional<SafeStateGuard> guard;
    if (guarded) guard.emplace();
    Station station(file);
    if (guard) {
      guard->add("laser off", [&] { station.laser.set(false); });
      guard->add("motor off", [&] { station.table.disable(); });
    }
    station.laser.set(true);
    station.table.rotate_by(5.0);
    [[maybe_unused]] auto n = write(ready[1], "R", 1);
    for (;;) pause();
  }
  close(ready[1]);
  char byte = 0;
  EXPECT_EQ(read(ready[0], &byte, 1), 1);
  close(ready[0]);
  EXPECT_EQ(sim::SimGpioChip::read_state_file(file), (std::vector<bool>{true, false, true, true})) << "child ready";
  kill(child, signal_number);
  int status = 0;
  waitpid(child, &status, 0);
  return {sim::SimGpioChip::read_state_file(file), WIFSIGNALED(status) ? WTERMSIG(status) : -1};
}

TEST(SafeState, SigtermLeavesTheChildsLinesOff) {
  const auto [levels, signal_number] = kill_child_station(SIGTERM, true);
  EXPECT_EQ(levels, (std::vector<bool>{false, false, true, false}));
  EXPECT_EQ(signal_number, SIGTERM) << "the child still dies of the signal";
}

TEST(SafeState, SigintLeavesTheChildsLinesOff) {
  const auto [levels, signal_number] = kill_child_station(SIGINT, true);
  EXPECT_EQ(levels, (std::vector<bool>{false, false, true, false}));
  EXPECT_EQ(signal_number, SIGINT);
}

TEST(SafeState, WithoutTheGuardAKilledChildLeavesTheLaserOn) {
  // The control experiment: this is what the guard prevents.
  const auto [levels, signal_number] = kill_child_station(SIGTERM, false);
  EXPECT_EQ(levels, (std::vector<bool>{true, false, true, true}));
  EXPECT_EQ(signal_number, SIGTERM);
}

}  // namespace
}  // namespace scanstation::drivers
