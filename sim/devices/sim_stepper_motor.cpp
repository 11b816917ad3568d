#include "sim/devices/sim_stepper_motor.h"

#include "core/errors.h"

#include <algorithm>

namespace scanstation::sim {

SimStepperMotor::SimStepperMotor(SimGpioChip& chip, SimStepperMotorConfig config)
    : chip_(chip), config_(config), step_(chip.offset_of("STEP")), direction_(chip.offset_of("DIR")),
      enable_(chip.offset_of("EN")), position_(config.start_position) {
  if (config_.steps_per_rev <= 0 || config_.switch_width <= 0 || config_.switch_width >= config_.steps_per_rev)
    throw InvalidInput("simulated stepper: steps_per_rev > switch_width > 0 expected");
  const auto& names = chip.line_names();
  if (const auto it = std::find(names.begin(), names.end(), "HOME"); it != names.end()) {
    home_ = static_cast<int>(it - names.begin());
    chip_.drive(static_cast<unsigned>(home_), at_home());
  }
  chip_.on_transition([this](const Transition& t) { on_transition(t); });
}

bool SimStepperMotor::at_home() const {
  const std::int64_t n = config_.steps_per_rev;
  const std::int64_t phase = ((position_.load() % n) + n) % n;
  return phase == 0 || phase > n - config_.switch_width;
}

void SimStepperMotor::on_transition(const Transition& transition) {
  // A step/dir driver moves one microstep on each rising STEP edge, in the
  // direction DIR holds at that moment (physical levels: DIR high = forward).
  if (transition.line != step_ || !transition.level) return;
  if (!chip_.level(enable_)) {
    ++lost_;
    return;
  }
  position_ += chip_.level(direction_) ? 1 : -1;
  if (home_ >= 0) chip_.drive(static_cast<unsigned>(home_), at_home());
}

}  // namespace scanstation::sim
