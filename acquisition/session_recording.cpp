#include "acquisition/session_recording.h"

#include "acquisition/stereo_step_points.h"

namespace scanstation::acquisition {

namespace {

using StepScan = std::function<int(int first_step, const StepSink& sink)>;
using StepPoints = std::function<std::vector<LaserScanPoints>(const CapturedStep&)>;

// The recording loop of every rig: `scan` captures the steps, each is
// recorded, its points computed for `on_step`, and the journal framed.
RecordingOutcome record_session(SessionRecorder& recorder, drivers::Clock& clock, const StepScan& scan,
                                const StepPoints& points, const RecordedStepSink& on_step, int stop_after,
                                const std::function<bool()>& stop_requested) {
  const SessionManifest& manifest = recorder.manifest();
  const int first = recorder.steps_done();
  recorder.event("scan_started",
                 {{"first_step", first}, {"steps", manifest.steps}, {"time_s", drivers::to_seconds(clock.now())}});
  RecordingOutcome outcome;
  const auto sink = [&](const CapturedStep& step) {
    recorder.record(step);
    ++outcome.recorded_now;
    if (on_step) on_step(step, points(step));
    if (stop_requested && stop_requested()) return false;
    return stop_after <= 0 || outcome.recorded_now < stop_after;
  };
  try {
    scan(first, sink);
  } catch (const std::exception& e) {
    // The steps recorded stay; the journal says why the run ended.
    recorder.event("scan_failed", {{"steps_done", recorder.steps_done()}, {"error", e.what()}});
    throw;
  }
  outcome.steps_done = recorder.steps_done();
  outcome.complete = outcome.steps_done == manifest.steps;
  recorder.event(outcome.complete ? "scan_finished" : "scan_stopped",
                 {{"steps_done", outcome.steps_done}, {"time_s", drivers::to_seconds(clock.now())}});
  return outcome;
}

}  // namespace

RecordingOutcome record_turntable_session(TurntableScanDevices& devices, SessionRecorder& recorder,
                                          const RecordedStepSink& on_step, int stop_after,
                                          const std::function<bool()>& stop_requested) {
  const SessionManifest& manifest = recorder.manifest();
  const auto points = [&](const CapturedStep& step) {
    StepFrames frames;
    frames.angle_deg = step.angle_deg;
    for (const CapturedFrame& f : step.frames) {
      if (!f.laser) {
        frames.off = f.frame.image;
      } else if (static_cast<std::size_t>(*f.laser) < manifest.geometry.lasers.size()) {
        frames.on.emplace_back(*f.laser, f.frame.image);
      }
    }
    return step_points(frames, manifest.geometry, manifest.parameters);
  };
  return record_session(
      recorder, devices.clock,
      [&](int first, const StepSink& sink) { return scan_turntable(devices, manifest.steps, first, sink); }, points,
      on_step, stop_after, stop_requested);
}

RecordingOutcome record_stereo_session(StereoScanDevices& devices, SessionRecorder& recorder,
                                       const RecordedStepSink& on_step, int stop_after,
                                       const std::function<bool()>& stop_requested) {
  const SessionManifest& manifest = recorder.manifest();
  const StereoScanSetup setup = stereo_scan_setup(manifest.geometry, manifest.stereo_parameters);
  const auto points = [&](const CapturedStep& step) {
    const StereoFrameRoles roles = stereo_frame_roles(step.frames);
    StereoStepFrames frames;
    frames.angle_deg = step.angle_deg;
    frames.left = step.frames.at(static_cast<std::size_t>(roles.left)).frame.image;
    frames.right = step.frames.at(static_cast<std::size_t>(roles.right)).frame.image;
    if (roles.colour >= 0) frames.colour = step.frames[static_cast<std::size_t>(roles.colour)].frame.image;
    return std::vector<LaserScanPoints>{stereo_step_points(frames, setup)};
  };
  return record_session(
      recorder, devices.clock,
      [&](int first, const StepSink& sink) { return scan_stereo(devices, manifest.steps, first, sink); }, points,
      on_step, stop_after, stop_requested);
}

}  // namespace scanstation::acquisition
