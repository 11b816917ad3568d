#include "drivers/frame_gate.h"

#include "drivers/device_error.h"

namespace scanstation::drivers {

SettledFrame grab_settled(Camera& camera, Clock& clock, Timestamp settled, std::chrono::milliseconds timeout) {
  const Timestamp deadline = clock.now() + timeout;
  SettledFrame result;
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - clock.now());
    if (left.count() <= 0)
      throw DeviceTimeout("no frame exposed after the state change from " + camera.description() + " within " +
                          std::to_string(timeout.count()) + " ms (" + std::to_string(result.discarded) +
                          " stale frames discarded)");
    result.frame = camera.grab_if(left, [settled](const Frame& frame) { return frame.exposure_start > settled; });
    if (result.frame.exposure_start > settled) return result;
    ++result.discarded;
  }
}

}  // namespace scanstation::drivers
