// Turntable: rotates the object in front of the camera. Implemented by a
// stepper on GPIO lines (drivers/stepper_turntable.h) and by a USB motion board
// (drivers/usb_controller.h).
#pragma once

#include "drivers/clock.h"

#include <string>

namespace scanstation::drivers {

class Turntable {
 public:
  virtual ~Turntable() = default;
  /// Turns by `degrees` (positive = the direction the DIR line calls forward)
  /// and returns when the motion has ended; the result is the moment the table
  /// has settled, the earliest time a frame may show the new pose.
  virtual Timestamp rotate_by(double degrees) = 0;
  /// Turns to the absolute angle by the shorter way round; returns as rotate_by.
  virtual Timestamp rotate_to(double degrees);
  /// The absolute angle in degrees (0 at power-up or at the home switch),
  /// counted exactly in motor steps.
  virtual double angle() const = 0;
  /// Seeks the home switch and sets the angle to 0 there; throws DeviceError
  /// when the table has no switch or the switch is not found within a turn.
  virtual Timestamp home() = 0;
  /// Cuts motor current (safe state); the next move re-enables it.
  virtual void disable() = 0;
  /// Cuts motor current for good: a move under way stops at its next step and
  /// every later move throws DeviceError. Called by the safe-state path from
  /// another thread, so implementations that move in the caller's thread must
  /// serialise it with their line writes (StepperTurntable, UsbController do);
  /// the default only disables.
  virtual void shut_down() { disable(); }
  virtual std::string describe() const = 0;
};

/// The rotation from `from` to `to` degrees by the shorter way, in (-180, 180].
double shortest_rotation(double from, double to);

}  // namespace scanstation::drivers
