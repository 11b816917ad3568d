#include "acquisition/session_recording.h"

namespace scanstation::acquisition {

RecordingOutcome record_turntable_session(TurntableScanDevices& devices, SessionRecorder& recorder,
                                          const RecordedStepSink& on_step, int stop_after,
                                          const std::function<bool()>& stop_requested) {
  const SessionManifest& manifest = recorder.manifest();
  const int first = recorder.steps_done();
  recorder.event("scan_started", {{"first_step", first},
                                  {"steps", manifest.steps},
                                  {"time_s", drivers::to_seconds(devices.clock.now())}});
  RecordingOutcome outcome;
  const auto sink = [&](const CapturedStep& step) {
    recorder.record(step);
    ++outcome.recorded_now;
    if (on_step) {
      StepFrames frames;
      frames.angle_deg = step.angle_deg;
      for (const CapturedFrame& f : step.frames) {
        if (!f.laser) {
          frames.off = f.frame.image;
        } else if (static_cast<std::size_t>(*f.laser) < manifest.geometry.lasers.size()) {
          frames.on.emplace_back(*f.laser, f.frame.image);
        }
      }
      on_step(step, step_points(frames, manifest.geometry, manifest.parameters));
    }
    if (stop_requested && stop_requested()) return false;
    return stop_after <= 0 || outcome.recorded_now < stop_after;
  };
  try {
    scan_turntable(devices, manifest.steps, first, sink);
  } catch (const std::exception& e) {
    // The steps recorded stay; the journal says why the run ended.
    recorder.event("scan_failed", {{"steps_done", recorder.steps_done()}, {"error", e.what()}});
    throw;
  }
  outcome.steps_done = recorder.steps_done();
  outcome.complete = outcome.steps_done == manifest.steps;
  recorder.event(outcome.complete ? "scan_finished" : "scan_stopped",
                 {{"steps_done", outcome.steps_done}, {"time_s", drivers::to_seconds(devices.clock.now())}});
  return outcome;
}

}  // namespace scanstation::acquisition
