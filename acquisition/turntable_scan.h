// The capture loop of a turntable laser scan, over the driver interfaces only
// (drivers/): the same code drives a real station and the simulated one.
//
// For each step: turn the table to the step's absolute angle; grab the
// laser-off frame; for each laser, switch it on, grab, switch it off. Every
// frame is accepted only through the frame gate (drivers/frame_gate.h): its
// exposure began after the last state change — table or laser — settled.
#pragma once

#include "drivers/camera.h"
#include "drivers/clock.h"
#include "drivers/laser.h"
#include "drivers/turntable.h"

#include <chrono>
#include <functional>
#include <optional>
#include <vector>

namespace scanstation::acquisition {

/// The devices a scan drives, borrowed (the caller owns them).
struct TurntableScanDevices {
  drivers::Camera& camera;
  std::vector<drivers::Laser*> lasers;
  drivers::Turntable& turntable;
  drivers::Clock& clock;
  std::chrono::milliseconds timeout{1000};  // longest wait for one settled frame
};

/// One accepted frame: `laser` is the laser lit (none for the laser-off frame),
/// `settled` the moment the state it shows had settled, `discarded` the stale
/// frames the gate threw away before it.
struct CapturedFrame {
  drivers::Frame frame;
  std::optional<int> laser;
  drivers::Timestamp settled{0};
  std::size_t discarded = 0;
};

/// One step: index, the table's angle (degrees, exact in motor steps), when the
/// move began and settled, the camera's exposure and gain, and the frames —
/// laser-off first, then one per laser in order.
struct CapturedStep {
  int step = 0;
  double angle_deg = 0;
  drivers::Timestamp move_start{0}, move_settled{0};
  std::int64_t exposure = 0, gain = 0;
  std::vector<CapturedFrame> frames;
};

/// Keeps the camera streaming for a scope, stopping it however the scope ends.
class CameraStreaming {
 public:
  explicit CameraStreaming(drivers::Camera& camera);
  ~CameraStreaming();
  CameraStreaming(const CameraStreaming&) = delete;
  CameraStreaming& operator=(const CameraStreaming&) = delete;

 private:
  drivers::Camera& camera_;
};

/// The frames of one pose of the table and the scene, the camera streaming:
/// the laser-off frame, then (with `lasers`) one frame per laser lit alone,
/// each accepted by the frame gate once what it shows has settled (after
/// `settled`, and after its laser switched). The lasers are left off.
std::vector<CapturedFrame> capture_laser_frames(TurntableScanDevices& devices, drivers::Timestamp settled,
                                                bool lasers = true);

/// Called after each step; returns false to stop the scan after it.
using StepSink = std::function<bool(const CapturedStep&)>;

/// Captures steps `first_step` .. `steps` − 1 of a turn divided into `steps`
/// equal angles (step k at k·360°/steps from the table's angle at the call,
/// turning forward only). Streams the
/// camera for the duration; lasers are left off. Returns the number of steps
/// captured. Device errors propagate (DeviceError, DeviceTimeout, DeviceGone).
int scan_turntable(TurntableScanDevices& devices, int steps, int first_step, const StepSink& sink);

}  // namespace scanstation::acquisition
