// A turntable driven by a step/dir stepper driver (A4988, DRV8825, TMC2209 in
// step/dir mode) on three digital lines, with an optional home switch.
#pragma once

#include "drivers/digital_io.h"
#include "drivers/turntable.h"

#include <cstdint>
#include <memory>
#include <mutex>

namespace scanstation::drivers {

struct StepperConfig {
  int full_steps_per_rev = 200;     // motor full steps per motor revolution
  int microsteps = 16;              // driver microstep setting (MS pins)
  double gear_ratio = 1.0;          // motor revolutions per table revolution
  double max_speed_deg_s = 60.0;    // table degrees per second
  double acceleration_deg_s2 = 120.0;
  double home_speed_deg_s = 10.0;   // constant speed while seeking the switch
  double home_overtravel_deg = 10.0;  // searched beyond one full turn before giving up
  Timestamp pulse_width = std::chrono::microseconds(5);   // STEP high time (driver minimum ~2 µs)
  Timestamp direction_setup = std::chrono::microseconds(5);  // DIR stable before the first STEP edge
  Timestamp enable_delay = std::chrono::milliseconds(2);  // driver wake-up after ENABLE
  Timestamp settle = std::chrono::milliseconds(100);      // table vibration after the last step

  /// Microsteps per table revolution.
  double steps_per_rev() const { return full_steps_per_rev * microsteps * gear_ratio; }
  /// Throws InvalidInput naming the first field out of range.
  void validate() const;
};

/// The lines of the stepper driver. `enable` is logical (active = motor powered);
/// give the LineAddress active_low for drivers whose EN pin is low-active.
struct StepperLines {
  std::unique_ptr<DigitalOutput> step;
  std::unique_ptr<DigitalOutput> direction;  // active = positive rotation
  std::unique_ptr<DigitalOutput> enable;
  std::unique_ptr<DigitalInput> home;        // optional; active = at home
};

class StepperTurntable final : public Turntable {
 public:
  StepperTurntable(StepperLines lines, Clock& clock, StepperConfig config);
  /// Disables the motor (safe state).
  ~StepperTurntable() override;
  StepperTurntable(const StepperTurntable&) = delete;
  StepperTurntable& operator=(const StepperTurntable&) = delete;

  Timestamp rotate_by(double degrees) override;
  double angle() const override;
  /// Seeks the switch backwards at home_speed_deg_s for at most one turn
  /// plus home_overtravel_deg; throws DeviceError naming the switch line when
  /// it never becomes active.
  Timestamp home() override;
  void disable() override;
  void shut_down() override;
  std::string describe() const override;

  /// Absolute position in microsteps.
  std::int64_t position() const { return position_; }

 private:
  void prepare(bool forward);
  void pulse(Timestamp at);
  /// Throws once shut_down() has run; call with mutex_ held.
  void require_running() const;

  StepperLines lines_;
  Clock& clock_;
  StepperConfig config_;
  std::int64_t position_ = 0;
  double commanded_ = 0;  // degrees: the sum of every requested move since home
  bool enabled_ = false;
  std::mutex mutex_;  // every line write, against shut_down() from the safe-state thread
  bool shut_down_ = false;
};

}  // namespace scanstation::drivers
