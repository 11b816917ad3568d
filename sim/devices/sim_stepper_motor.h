// The mechanical side of a simulated stepper turntable: it watches the STEP,
// DIR and EN lines of a simulated GPIO chip like a step/dir driver would, counts
// the table's physical position, and drives the HOME input line while the table
// stands at its home angle. Steps issued while EN is inactive are lost, as on a
// real driver, so a test can tell commanded from physical motion.
#pragma once

#include "sim/devices/sim_gpio_chip.h"

#include <atomic>
#include <cstdint>

namespace scanstation::sim {

struct SimStepperMotorConfig {
  std::int64_t steps_per_rev = 200 * 16;  // microsteps per table revolution
  std::int64_t start_position = 0;         // physical position at power-up, microsteps from home
  std::int64_t switch_width = 8;           // microsteps over which the switch is closed
};

class SimStepperMotor {
 public:
  /// Follows lines STEP, DIR, EN of `chip` and drives its line HOME (when the
  /// chip has one). The chip must outlive the motor's use; the motor must
  /// outlive the chip's transitions (keep it next to the chip).
  SimStepperMotor(SimGpioChip& chip, SimStepperMotorConfig config);

  /// Physical position in microsteps (unbounded; a whole turn is steps_per_rev).
  std::int64_t position() const { return position_.load(); }
  /// Steps the driver received while disabled (lost).
  std::int64_t lost_steps() const { return lost_.load(); }
  /// True while the home switch is closed: the physical position modulo a turn
  /// lies in (−switch_width, 0], so moving backwards it closes exactly at 0.
  bool at_home() const;

 private:
  void on_transition(const Transition& transition);

  SimGpioChip& chip_;
  SimStepperMotorConfig config_;
  unsigned step_, direction_, enable_;
  int home_ = -1;  // line offset, -1 without a HOME line
  std::atomic<std::int64_t> position_;
  std::atomic<std::int64_t> lost_{0};
};

}  // namespace scanstation::sim
