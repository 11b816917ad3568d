#include "acquisition/turntable_scan.h"

#include "core/errors.h"
#include "drivers/frame_gate.h"

#include <algorithm>

namespace scanstation::acquisition {

StreamingCamera::StreamingCamera(drivers::Camera& camera) : camera_(camera) { camera_.start(); }

StreamingCamera::~StreamingCamera() {
  try {
    camera_.stop();
  } catch (...) {
  }
}

CapturedFrame grab_frame(drivers::Camera& camera, drivers::Clock& clock, drivers::Timestamp settled,
                         std::chrono::milliseconds timeout) {
  drivers::SettledFrame got = drivers::grab_settled(camera, clock, settled, timeout);
  CapturedFrame frame;
  frame.frame = std::move(got.frame);
  frame.settled = settled;
  frame.discarded = got.discarded;
  return frame;
}

CapturedStep turn_for_step(drivers::Turntable& turntable, drivers::Clock& clock, drivers::Camera& camera, int step,
                           double move_deg) {
  CapturedStep captured;
  captured.step = step;
  captured.move_start = clock.now();
  captured.move_settled = turntable.rotate_by(move_deg);
  captured.angle_deg = turntable.angle();
  captured.exposure = camera.control("exposure");
  captured.gain = camera.control("gain");
  return captured;
}

int turn_through_steps(int steps, int first_step, const StepCapture& capture, const StepSink& sink) {
  if (steps < 1) throw InvalidInput("turntable scan: the number of steps must be at least 1");
  if (first_step < 0 || first_step > steps)
    throw InvalidInput("turntable scan: first step " + std::to_string(first_step) + " outside 0.." +
                       std::to_string(steps));
  int captured = 0;
  // Always forward, to the step's absolute place on the turn (the table's
  // zero is where this run started): a resumed scan turns straight to its
  // first step and reaches the very motor positions an uninterrupted one did.
  double at = 0;
  for (int step = first_step; step < steps; ++step) {
    const double target = 360.0 * step / steps;
    const CapturedStep result = capture(step, target - at);
    at = target;
    ++captured;
    if (!sink(result)) break;
  }
  return captured;
}

std::vector<CapturedFrame> capture_laser_frames(TurntableScanDevices& devices, drivers::Timestamp settled,
                                                bool lasers) {
  const auto grab = [&](drivers::Timestamp after, std::optional<int> laser) {
    CapturedFrame frame = grab_frame(devices.camera, devices.clock, after, devices.timeout);
    frame.laser = laser;
    return frame;
  };
  for (drivers::Laser* laser : devices.lasers)
    if (laser->is_on()) settled = std::max(settled, laser->set(false));
  std::vector<CapturedFrame> frames;
  frames.push_back(grab(settled, std::nullopt));
  for (std::size_t i = 0; lasers && i < devices.lasers.size(); ++i) {
    const drivers::Timestamp lit = devices.lasers[i]->set(true);
    frames.push_back(grab(std::max(settled, lit), static_cast<int>(i)));
    // The next frame must not show this laser's afterglow either.
    settled = devices.lasers[i]->set(false);
  }
  return frames;
}

int scan_turntable(TurntableScanDevices& devices, int steps, int first_step, const StepSink& sink) {
  const StreamingCamera streaming(devices.camera);
  const int captured = turn_through_steps(steps, first_step, [&](int step, double move_deg) {
    CapturedStep captured = turn_for_step(devices.turntable, devices.clock, devices.camera, step, move_deg);
    captured.frames = capture_laser_frames(devices, captured.move_settled);
    return captured;
  }, sink);
  for (drivers::Laser* laser : devices.lasers) laser->set(false);
  return captured;
}

}  // namespace scanstation::acquisition
