// The capture loop of a turntable stereo scan, over the driver interfaces
// only (drivers/): the same code drives a real stereo station and the
// simulated one.
//
// For each step: turn the table to the step's absolute angle; switch the
// projector on and grab a settled frame from each camera; switch it off and
// grab the left camera again for the colours (the dots would paint them).
// The projector is a light on a digital output like a laser (drivers/laser.h),
// so a real station wires it to a GPIO line or a USB board output.
#pragma once

#include "acquisition/turntable_scan.h"

namespace scanstation::acquisition {

/// The devices a stereo scan drives, borrowed (the caller owns them).
/// projector     none: passive stereo, one pair per step and no colour frame
/// colour_frame  with a projector: also the left camera with it off
struct StereoScanDevices {
  drivers::Camera& left;
  drivers::Camera& right;
  drivers::Laser* projector = nullptr;
  drivers::Turntable& turntable;
  drivers::Clock& clock;
  std::chrono::milliseconds timeout{1000};  // longest wait for one settled frame
  bool colour_frame = true;
};

/// Captures steps `first_step` .. `steps` − 1 as scan_turntable does; each
/// step's frames are left (camera 0), right (camera 1), both with the
/// projector on when there is one, then the colour frame (camera 0,
/// projector off). Streams both cameras for the duration; the projector is
/// left off. Returns the number of steps captured. Device errors propagate.
int scan_stereo(StereoScanDevices& devices, int steps, int first_step, const StepSink& sink);

}  // namespace scanstation::acquisition
