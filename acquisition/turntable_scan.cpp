#include "acquisition/turntable_scan.h"

#include "core/errors.h"
#include "drivers/frame_gate.h"

#include <algorithm>

namespace scanstation::acquisition {

namespace {

CapturedFrame grab(TurntableScanDevices& devices, drivers::Timestamp settled, std::optional<int> laser) {
  drivers::SettledFrame got = drivers::grab_settled(devices.camera, devices.clock, settled, devices.timeout);
  return {std::move(got.frame), laser, settled, got.discarded};
}

CapturedStep capture_step(TurntableScanDevices& devices, int step, double move_deg) {
  CapturedStep captured;
  captured.step = step;
  captured.move_start = devices.clock.now();
  captured.move_settled = devices.turntable.rotate_by(move_deg);
  captured.angle_deg = devices.turntable.angle();
  captured.exposure = devices.camera.control("exposure");
  captured.gain = devices.camera.control("gain");
  captured.frames = capture_laser_frames(devices, captured.move_settled);
  return captured;
}

}  // namespace

CameraStreaming::CameraStreaming(drivers::Camera& camera) : camera_(camera) { camera_.start(); }

CameraStreaming::~CameraStreaming() {
  try {
    camera_.stop();
  } catch (...) {
  }
}

std::vector<CapturedFrame> capture_laser_frames(TurntableScanDevices& devices, drivers::Timestamp settled,
                                                bool lasers) {
  for (drivers::Laser* laser : devices.lasers)
    if (laser->is_on()) settled = std::max(settled, laser->set(false));
  std::vector<CapturedFrame> frames;
  frames.push_back(grab(devices, settled, std::nullopt));
  for (std::size_t i = 0; lasers && i < devices.lasers.size(); ++i) {
    const drivers::Timestamp lit = devices.lasers[i]->set(true);
    frames.push_back(grab(devices, std::max(settled, lit), static_cast<int>(i)));
    // The next frame must not show this laser's afterglow either.
    settled = devices.lasers[i]->set(false);
  }
  return frames;
}

int scan_turntable(TurntableScanDevices& devices, int steps, int first_step, const StepSink& sink) {
  if (steps < 1) throw InvalidInput("turntable scan: the number of steps must be at least 1");
  if (first_step < 0 || first_step > steps)
    throw InvalidInput("turntable scan: first step " + std::to_string(first_step) + " outside 0.." +
                       std::to_string(steps));
  CameraStreaming streaming(devices.camera);
  int captured = 0;
  // Always forward, to the step's absolute place on the turn (the table's
  // zero is where this run started): a resumed scan turns straight to its
  // first step and reaches the very motor positions an uninterrupted one did.
  double at = 0;
  for (int step = first_step; step < steps; ++step) {
    const double target = 360.0 * step / steps;
    const CapturedStep result = capture_step(devices, step, target - at);
    at = target;
    ++captured;
    if (!sink(result)) break;
  }
  for (drivers::Laser* laser : devices.lasers) laser->set(false);
  return captured;
}

}  // namespace scanstation::acquisition
