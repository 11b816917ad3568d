// Time in the device layer: nanoseconds on CLOCK_MONOTONIC, the clock V4L2
// stamps its buffers with, so actuator events and frame timestamps compare
// directly. The simulator substitutes a virtual clock (sim/devices/virtual_clock.h)
// so timing tests are exact and never depend on the wall clock.
#pragma once

#include <chrono>

namespace scanstation::drivers {

/// A point in time: nanoseconds since an arbitrary monotonic epoch.
using Timestamp = std::chrono::nanoseconds;

class Clock {
 public:
  virtual ~Clock() = default;
  virtual Timestamp now() const = 0;
  /// Returns at `when` or later (immediately when `when` is past).
  virtual void sleep_until(Timestamp when) = 0;
};

/// CLOCK_MONOTONIC of the running system.
class MonotonicClock final : public Clock {
 public:
  Timestamp now() const override;
  void sleep_until(Timestamp when) override;
};

/// Seconds as a Timestamp (rounded to the nearest nanosecond).
inline Timestamp seconds(double s) { return Timestamp(static_cast<long long>(s * 1e9 + (s >= 0 ? 0.5 : -0.5))); }
inline double to_seconds(Timestamp t) { return static_cast<double>(t.count()) * 1e-9; }

}  // namespace scanstation::drivers
