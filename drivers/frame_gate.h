// Frame-state integrity: after the laser switches or the table moves, frames
// already exposed (or queued in driver buffers) still show the old state.
// Instead of discarding a fixed number of frames, a frame is accepted only when
// its exposure began after the state change settled, judged by the driver's
// own timestamp on the same monotonic clock.
#pragma once

#include "drivers/camera.h"

#include <chrono>
#include <cstddef>

namespace scanstation::drivers {

struct SettledFrame {
  Frame frame;
  std::size_t discarded = 0;  // stale frames grabbed and thrown away first
};

/// The first frame whose exposure_start is after `settled`. Waits at most
/// `timeout` in total, then throws DeviceTimeout.
SettledFrame grab_settled(Camera& camera, Clock& clock, Timestamp settled, std::chrono::milliseconds timeout);

}  // namespace scanstation::drivers
