// A line laser on a digital output, with the time its light takes to settle
// after switching (driver rise time, thermal start-up of cheap modules).
#pragma once

#include "drivers/clock.h"
#include "drivers/digital_io.h"

#include <memory>

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
  Timestamp set(bool on);
  bool is_on() const { return output_->value(); }
  std::string describe() const { return output_->describe(); }

 private:
  std::unique_ptr<DigitalOutput> output_;
  Clock& clock_;
  Timestamp settle_;
};

}  // namespace scanstation::drivers
