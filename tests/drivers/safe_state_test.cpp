// Safe state: lasers off and the motor disabled when the program ends by an
// exception or is killed with SIGTERM/SIGINT. The signal tests fork a child
// that holds a simulated GPIO chip mirrored into a state file, kill it, and
// read the levels the child left behind.
#include "core/errors.h"
#include "drivers/device_error.h"
#include "drivers/laser.h"
#include "drivers/safe_state.h"
#include "drivers/stepper_turntable.h"
#include "sim/devices/sim_gpio_chip.h"
#include "sim/devices/virtual_clock.h"
#include "test_support.h"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <csignal>
#include <fcntl.h>
#include <fstream>
#include <mutex>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

namespace scanstation::drivers {
namespace {

using namespace std::chrono_literals;

// Virtual time that a test can stop: while held, a sleep waits until the
// test lets go. The turntable sleeps between its steps outside its lock, so
// a thread held there leaves the lock free for another thread's shut_down(),
// which then lands between two steps for certain, however the scheduler runs
// the threads.
class HoldableClock final : public Clock {
 public:
  Timestamp now() const override { return time_.now(); }
  void sleep_until(Timestamp when) override {
    {
      std::unique_lock lock(mutex_);
      released_.wait(lock, [&] { return !held_; });
    }
    time_.sleep_until(when);
  }
  void hold() {
    std::lock_guard lock(mutex_);
    held_ = true;
  }
  void release() {
    {
      std::lock_guard lock(mutex_);
      held_ = false;
    }
    released_.notify_all();
  }

 private:
  sim::VirtualClock time_;
  std::mutex mutex_;
  std::condition_variable released_;
  bool held_ = false;
};

// Laser on line 0, stepper STEP/DIR/EN on 1..3.
struct Station {
  HoldableClock clock;
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

TEST(SafeState, ShutDownLatchesLaserTurntableAndBoardOff) {
  Station station;
  station.laser.set(true);
  station.table.rotate_by(10.0);
  station.laser.shut_down();
  station.table.shut_down();
  EXPECT_FALSE(station.chip.level(0));
  EXPECT_FALSE(station.chip.level(3));
  test::expect_error<DeviceError>([&] { station.laser.set(true); }, {"LASER0", "held off by the safe state"});
  EXPECT_NO_THROW(station.laser.set(false));
  test::expect_error<DeviceError>([&] { station.table.rotate_by(10.0); }, {"stopped by the safe state"});
  EXPECT_FALSE(station.chip.level(3)) << "the refused move did not enable the motor";
}

// Records the order of every transition of a chip (the listener runs inside
// the writer's own lock, so the order is the order of the writes).
struct TransitionLog {
  std::mutex mutex;
  std::vector<sim::Transition> transitions;
  void attach(sim::SimGpioChip& chip) {
    chip.on_transition([this](const sim::Transition& t) {
      std::lock_guard lock(mutex);
      transitions.push_back(t);
    });
  }
};

// After the first moment `line` went low, no line in `active_lines` went high again.
void expect_nothing_active_after_off(const std::vector<sim::Transition>& log, unsigned line,
                                     std::initializer_list<unsigned> active_lines) {
  const auto off = std::find_if(log.begin(), log.end(), [&](const auto& t) { return t.line == line && !t.level; });
  ASSERT_NE(off, log.end()) << "line " << line << " was never switched off";
  for (auto it = off; it != log.end(); ++it)
    for (const unsigned l : active_lines)
      EXPECT_FALSE(it->line == l && it->level) << "line " << l << " went high after line " << line << " went off";
}

TEST(SafeState, ShutDownFromAnotherThreadStopsAMoveAtItsNextStep) {
  Station station;
  TransitionLog log;
  log.attach(station.chip);
  // At the 100th step the moving thread is held in its next sleep until the
  // other thread has shut everything down: the move cannot run to its end
  // first, however late that thread is scheduled.
  std::atomic<int> edges{0};
  station.chip.on_transition([&](const sim::Transition& t) {
    if (t.line == 1 && t.level && ++edges == 100) station.clock.hold();
  });
  std::thread safe_state([&] {
    while (edges.load() < 100) std::this_thread::yield();
    station.laser.shut_down();
    station.table.shut_down();
    station.clock.release();
  });
  station.laser.set(true);
  test::expect_error<DeviceError>([&] { station.table.rotate_by(36000.0); }, {"stopped by the safe state"});
  safe_state.join();
  EXPECT_LT(station.table.position(), 320000) << "the move ended early";
  EXPECT_EQ(station.table.position(), 100) << "at the step after the shut-down";
  EXPECT_GE(station.table.position(), 100);
  std::lock_guard lock(log.mutex);
  expect_nothing_active_after_off(log.transitions, 3, {1, 3});
  EXPECT_FALSE(station.chip.level(0));
  EXPECT_FALSE(station.chip.level(1));
  EXPECT_FALSE(station.chip.level(3));
}

// A child moves the table in real time with the laser on, reporting its
// transitions to a journal file (written inside the writers' locks, so in
// order), and is killed with SIGTERM after `delay` of motion. Returns the
// levels and the journal it left.
struct KilledChild {
  std::vector<bool> levels;
  std::vector<sim::Transition> journal;
  int signal_number = -1;
};

KilledChild kill_child_mid_move(std::chrono::microseconds delay, bool report_before_requests = false) {
  test::ScratchFolder folder;
  const auto file = folder / "lines", journal_file = folder / "journal";
  int ready[2];
  if (pipe(ready) != 0) throw std::runtime_error("pipe");
  const pid_t child = fork();
  if (child == 0) {
    close(ready[0]);
    SafeStateGuard guard;  // before the lines are requested: a signal during the requests is handled too
    if (report_before_requests) [[maybe_unused]] auto n = write(ready[1], "R", 1);
    MonotonicClock clock;
    sim::SimGpioChip chip("simchip0", {"LASER0", "STEP", "DIR", "EN"}, clock, file);
    const int journal = open(journal_file.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    bool reported = false;
    chip.on_transition([&](const sim::Transition& t) {
      const std::string line = std::to_string(t.line) + " " + (t.level ? "1" : "0") + "\n";
      [[maybe_unused]] auto n = write(journal, line.data(), line.size());
      if (t.line == 1 && t.level && !reported && !report_before_requests) {
        reported = true;  // the first step edge: the move is under way
        n = write(ready[1], "R", 1);
      }
    });
    Laser laser(chip.request_output({"", 0u, ""}, "test", false), clock, 1ms);
    StepperConfig config;
    // Fast stepping (a pulse every ~30 µs) keeps the main thread writing
    // lines while the watcher works (the latch itself is shown
    // deterministically by ShutDownFromAnotherThreadStopsAMoveAtItsNextStep).
    config.max_speed_deg_s = 3600;
    config.acceleration_deg_s2 = 36000;  // 100 turns take 10 s: killed long before the end
    StepperTurntable table(StepperLines{chip.request_output({"", 1u, ""}, "test", false),
                                        chip.request_output({"", 2u, ""}, "test", false),
                                        chip.request_output({"", 3u, ""}, "test", false), nullptr},
                           clock, config);
    guard.add("laser off", [&] { laser.shut_down(); });
    guard.add("motor off", [&] { table.shut_down(); });
    try {
      laser.set(true);
      table.rotate_by(36000.0);
    } catch (const DeviceError&) {
      // stopped by the safe state; the guard ends the process
    }
    for (;;) pause();
  }
  close(ready[1]);
  char byte = 0;
  EXPECT_EQ(read(ready[0], &byte, 1), 1) << "the child started moving";
  close(ready[0]);
  std::this_thread::sleep_for(delay);
  kill(child, SIGTERM);
  int status = 0;
  waitpid(child, &status, 0);
  KilledChild result;
  if (std::filesystem::exists(file)) result.levels = sim::SimGpioChip::read_state_file(file);  // else killed before the chip existed
  result.signal_number = WIFSIGNALED(status) ? WTERMSIG(status) : -1;
  std::ifstream in(journal_file);
  for (unsigned line = 0, level = 0; in >> line >> level;) result.journal.push_back({line, level == 1, {}});
  return result;
}

TEST(SafeState, SigtermMidMoveLeavesTheLinesOffAndTheJournalShowsNoLaterActivity) {
  // Several kill moments, from the first step on, to hit the signal at
  // different points of the pulse loop.
  for (const auto delay : {0us, 300us, 2000us, 15000us}) {
    const KilledChild child = kill_child_mid_move(delay);
    EXPECT_EQ(child.signal_number, SIGTERM) << "the child still dies of the signal";
    ASSERT_EQ(child.levels.size(), 4u);
    EXPECT_FALSE(child.levels[0]) << "laser off after a kill " << delay.count() << " µs into the move";
    EXPECT_FALSE(child.levels[1]) << "STEP low";
    EXPECT_FALSE(child.levels[3]) << "motor disabled";
    ASSERT_FALSE(child.journal.empty());
    EXPECT_GT(std::count_if(child.journal.begin(), child.journal.end(), [](const auto& t) { return t.line == 1 && t.level; }),
              0) << "the child was stepping";
    expect_nothing_active_after_off(child.journal, 3, {0, 1, 3});
    expect_nothing_active_after_off(child.journal, 0, {0});
  }
}

TEST(SafeState, SigtermWhileTheLinesAreRequestedStillEndsSafe) {
  // The child reports before it opens anything; the kill lands while the chip
  // is created, the lines are requested, the actions registered or the laser
  // switched on. Whatever the moment, nothing is left on.
  for (const auto delay : {0us, 20us, 50us, 100us, 200us, 400us}) {
    const KilledChild child = kill_child_mid_move(delay, true);
    EXPECT_EQ(child.signal_number, SIGTERM);
    for (std::size_t line : {0u, 1u, 3u}) {
      if (line < child.levels.size()) {
        EXPECT_FALSE(child.levels[line]) << "line " << line << ", kill after " << delay.count() << " µs";
      }
    }
    // The safe state's mark in the journal: the motor switched off, or the
    // laser when the kill came before the motor was ever enabled (then
    // nothing of the motor was on to switch off).
    const auto went_high = [&](unsigned line) {
      return std::any_of(child.journal.begin(), child.journal.end(),
                         [&](const sim::Transition& t) { return t.line == line && t.level; });
    };
    if (went_high(3)) {
      expect_nothing_active_after_off(child.journal, 3, {0, 1, 3});
    } else if (went_high(0)) {
      expect_nothing_active_after_off(child.journal, 0, {0, 1, 3});
    } else {
      EXPECT_FALSE(went_high(1)) << "a step before the motor was enabled, kill after " << delay.count() << " µs";
    }
  }
}

}  // namespace
}  // namespace scanstation::drivers

namespace scanstation::drivers {
namespace {

TEST(SafeState, StopWorkGuardMakesSafeAndLetsTheWorkFinish) {
  std::atomic<int> actions{0};
  {
    SafeStateGuard guard(OnSignal::stop_work);
    guard.add("count", [&] { ++actions; });
    EXPECT_EQ(guard.signal_received(), 0);
    raise(SIGINT);  // the process goes on: the work sees the signal and stops by itself
    while (guard.signal_received() == 0) std::this_thread::sleep_for(1ms);  // the watcher records it
    EXPECT_EQ(guard.signal_received(), SIGINT);
    EXPECT_GE(actions.load(), 1) << "the safe state came first";
  }
  EXPECT_GE(actions.load(), 2) << "and once more when the guard ends";
}

}  // namespace
}  // namespace scanstation::drivers
