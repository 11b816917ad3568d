// A line laser on a digital output, with the time its light takes to settle
// after switching (driver rise time, thermal start-up of cheap modules).
#pragma once

#include "drivers/clock.h"
#include "drivers/digital_io.h"

#include <memory>
#include <mutex>

namespace scanstation::drivers {

class Laser {
 public:
  /// The output is switched off first: a laser starts in its safe state.
  Laser(std::unique_ptr<DigitalOutput> output, Clock& clock, Timestamp settle);
  /// Switches off (safe state).
  ~Laser();
  Laser(const Laser&) = delete;
  Laser& operator=(const Laser&) = delete;

  /// Switches and returns the moment the light is stable; a frame whose
  /// exposure starts earlier may show the old state (see frame_gate.h).
  /// Throws DeviceError for `on` after shut_down().
  Timestamp set(bool on);
  /// Switches off for good: every later set(true) throws. The safe-state path
  /// calls this from another thread (drivers/safe_state.h); set() and
  /// shut_down() are serialised, so a switch-on racing with it cannot win.
  void shut_down();
  bool is_on() const { return output_->value(); }
  std::string describe() const { return output_->describe(); }

 private:
  std::unique_ptr<DigitalOutput> output_;
  Clock& clock_;
  Timestamp settle_;
  std::mutex mutex_;
  bool shut_down_ = false;
};

}  // namespace scanstation::drivers
