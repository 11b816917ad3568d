// Recording a turntable scan into a session: the capture loop
// (turntable_scan.h, stereo_scan.h) with each step written to the session as
// soon as it is captured, and its points computed live for progress and live
// views.
#pragma once

#include "acquisition/session.h"
#include "acquisition/stereo_scan.h"
#include "acquisition/turntable_step_points.h"

#include <functional>

namespace scanstation::acquisition {

/// Called after each recorded step with its live points (one cloud per laser,
/// or the stereo pair's one cloud; object frame of the platter).
using RecordedStepSink = std::function<void(const CapturedStep&, const std::vector<LaserScanPoints>&)>;

/// recorded_now  steps captured by this call
/// steps_done    steps the session holds now
/// complete      every planned step is recorded
struct RecordingOutcome {
  int recorded_now = 0;
  int steps_done = 0;
  bool complete = false;
};

/// Captures the steps `recorder` still lacks (from recorder.steps_done() on)
/// and records each. `stop_after` > 0 stops after that many steps (a scan in
/// parts; the session stays resumable); so does `stop_requested` returning
/// true after a step (an operator's Ctrl-C). Journal events scan_started and
/// scan_finished / scan_stopped frame the run; a device error propagates
/// after every completed step has been recorded.
RecordingOutcome record_turntable_session(TurntableScanDevices& devices, SessionRecorder& recorder,
                                          const RecordedStepSink& on_step = {}, int stop_after = 0,
                                          const std::function<bool()>& stop_requested = {});

/// record_turntable_session for a stereo rig (manifest rig "stereo", its
/// geometry's two cameras and stereo parameters): each step's points are the
/// pair's (stereo_step_points).
RecordingOutcome record_stereo_session(StereoScanDevices& devices, SessionRecorder& recorder,
                                       const RecordedStepSink& on_step = {}, int stop_after = 0,
                                       const std::function<bool()>& stop_requested = {});

}  // namespace scanstation::acquisition
