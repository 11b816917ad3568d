#include "acquisition/stereo_scan.h"

#include <algorithm>

namespace scanstation::acquisition {

namespace {

CapturedStep capture_stereo_step(StereoScanDevices& devices, int step, double move_deg) {
  CapturedStep captured = turn_for_step(devices.turntable, devices.clock, devices.left, step, move_deg);
  const bool projector = devices.projector != nullptr;
  drivers::Timestamp settled = captured.move_settled;
  if (projector) settled = std::max(settled, devices.projector->set(true));
  for (const int camera : {0, 1}) {
    CapturedFrame frame =
        grab_frame(camera == 0 ? devices.left : devices.right, devices.clock, settled, devices.timeout);
    frame.camera = camera;
    frame.projector = projector;
    captured.frames.push_back(std::move(frame));
  }
  if (projector && devices.colour_frame) {
    // Not a frame showing the dots' afterglow either.
    CapturedFrame colour = grab_frame(devices.left, devices.clock, devices.projector->set(false), devices.timeout);
    colour.camera = 0;
    captured.frames.push_back(std::move(colour));
  }
  return captured;
}

}  // namespace

int scan_stereo(StereoScanDevices& devices, int steps, int first_step, const StepSink& sink) {
  const StreamingCamera left(devices.left), right(devices.right);
  const int captured = turn_through_steps(
      steps, first_step, [&](int step, double move_deg) { return capture_stereo_step(devices, step, move_deg); },
      sink);
  if (devices.projector) devices.projector->set(false);
  return captured;
}

}  // namespace scanstation::acquisition
