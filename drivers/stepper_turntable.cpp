#include "drivers/stepper_turntable.h"

#include "core/errors.h"
#include "core/log.h"
#include "drivers/device_error.h"
#include "drivers/trapezoid_ramp.h"

#include <cmath>
#include <spdlog/fmt/fmt.h>

namespace scanstation::drivers {

void StepperConfig::validate() const {
  auto require = [](bool ok, const char* field, const char* expected) {
    if (!ok) throw InvalidInput(std::string("stepper ") + field + ": expected " + expected);
  };
  require(full_steps_per_rev > 0, "full_steps_per_rev", "a positive integer");
  require(microsteps >= 1 && microsteps <= 256, "microsteps", "1..256");
  require(gear_ratio > 0, "gear_ratio", "a positive number");
  require(max_speed_deg_s > 0, "max_speed_deg_s", "a positive number");
  require(acceleration_deg_s2 > 0, "acceleration_deg_s2", "a positive number");
  require(home_speed_deg_s > 0, "home_speed_deg_s", "a positive number");
  require(home_overtravel_deg >= 0, "home_overtravel_deg", "a non-negative number");
  require(pulse_width.count() > 0, "pulse_width", "a positive time");
}

StepperTurntable::StepperTurntable(StepperLines lines, Clock& clock, StepperConfig config)
    : lines_(std::move(lines)), clock_(clock), config_(config) {
  config_.validate();
  if (!lines_.step || !lines_.direction || !lines_.enable)
    throw InvalidInput("stepper turntable needs step, direction and enable lines");
}

StepperTurntable::~StepperTurntable() {
  try {
    disable();
  } catch (const std::exception& e) {
    room_logger("drivers")->error("could not disable the turntable motor: {}", e.what());
  }
}

void StepperTurntable::disable() {
  std::lock_guard lock(mutex_);
  lines_.enable->set(false);
  lines_.step->set(false);
  enabled_ = false;
}

void StepperTurntable::shut_down() {
  std::lock_guard lock(mutex_);
  shut_down_ = true;
  lines_.enable->set(false);
  lines_.step->set(false);
  enabled_ = false;
}

void StepperTurntable::require_running() const {
  if (shut_down_) throw DeviceError("turntable " + describe() + " was stopped by the safe state");
}

void StepperTurntable::prepare(bool forward) {
  Timestamp ready;
  {
    std::lock_guard lock(mutex_);
    require_running();
    lines_.direction->set(forward);
    ready = clock_.now() + config_.direction_setup;
    if (!enabled_) {
      lines_.enable->set(true);
      enabled_ = true;
      ready = std::max(ready, clock_.now() + config_.enable_delay);
    }
  }
  clock_.sleep_until(ready);
}

void StepperTurntable::pulse(Timestamp at) {
  clock_.sleep_until(at);
  {
    // Checked under the lock with the rising edge: once shut_down() has run
    // no further step can be issued.
    std::lock_guard lock(mutex_);
    require_running();
    lines_.step->set(true);
  }
  clock_.sleep_until(clock_.now() + config_.pulse_width);
  std::lock_guard lock(mutex_);
  lines_.step->set(false);
}

Timestamp StepperTurntable::rotate_by(double degrees) {
  if (!std::isfinite(degrees)) throw InvalidInput("turntable rotation must be a finite number of degrees");
  const double per_degree = config_.steps_per_rev() / 360.0;
  // Round the commanded angle, not each move, so many small moves never
  // drift from the absolute angle.
  commanded_ += degrees;
  const auto target = static_cast<std::int64_t>(std::llround(commanded_ * per_degree));
  const std::int64_t steps = target - position_;
  if (steps == 0) return clock_.now();
  prepare(steps > 0);
  const auto times = trapezoid_step_times(std::llabs(steps), config_.max_speed_deg_s * per_degree,
                                          config_.acceleration_deg_s2 * per_degree);
  const Timestamp start = clock_.now();
  const std::int64_t direction = steps > 0 ? 1 : -1;
  for (const double t : times) {
    // Issue the edge at the ideal time but never closer than a full pulse
    // period to the previous one (slow clocks, huge speeds).
    pulse(std::max(start + seconds(t), clock_.now() + config_.pulse_width));
    position_ += direction;
  }
  return clock_.now() + config_.settle;
}

double StepperTurntable::angle() const { return static_cast<double>(position_) * 360.0 / config_.steps_per_rev(); }

Timestamp StepperTurntable::home() {
  if (!lines_.home) throw DeviceError("turntable " + describe() + " has no home switch");
  const double per_degree = config_.steps_per_rev() / 360.0;
  const double travel_deg = 360.0 + config_.home_overtravel_deg;
  const auto limit = static_cast<std::int64_t>(std::ceil(travel_deg * per_degree));
  const Timestamp period = seconds(1.0 / (config_.home_speed_deg_s * per_degree));
  // 0 is where the switch closes while turning backwards: the same edge every
  // time, whatever the switch's width. Standing on it, leave it forwards first.
  if (lines_.home->value()) {
    prepare(true);
    for (std::int64_t i = 0; lines_.home->value(); ++i) {
      if (i == limit)
        throw DeviceError(fmt::format("home switch {} stays active over {:.1f}° of travel: stuck closed or wired to "
                                      "the wrong line",
                                      lines_.home->describe(), travel_deg));
      pulse(clock_.now() + period);
      ++position_;
    }
  }
  prepare(false);
  for (std::int64_t i = 0; i < limit; ++i) {
    pulse(clock_.now() + period);
    --position_;
    if (lines_.home->value()) {
      position_ = 0;
      commanded_ = 0;
      return clock_.now() + config_.settle;
    }
  }
  throw DeviceError(fmt::format("home switch {} did not become active within {:.1f}° ({} steps) of backwards travel: "
                                "check the switch and its wiring",
                                lines_.home->describe(), travel_deg, limit));
}

std::string StepperTurntable::describe() const {
  return "stepper (step " + lines_.step->describe() + ", dir " + lines_.direction->describe() + ", enable " +
         lines_.enable->describe() + ")";
}

}  // namespace scanstation::drivers
