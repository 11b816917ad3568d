#include "scan_job.h"

#include "acquisition/point_spacing.h"
#include "acquisition/session_recording.h"
#include "acquisition/station_calibration.h"
#include "core/errors.h"
#include "core/io/mesh_io.h"
#include "core/version.h"
#include "sim/scan_objects.h"
#include "sim/simulated_stereo.h"
#include "sim/simulated_turntable.h"

#include <cmath>
#include <csignal>
#include <cstdio>

namespace scanstation::app {

namespace {

using acquisition::SessionRecorder;

SessionRecorder resume_session(CommandContext& context, const ScanJob& job) {
  SessionRecorder recorder = SessionRecorder::resume(job.folder);
  const auto& m = recorder.manifest();
  if (job.steps_given && job.steps != m.steps)
    throw InvalidInput("--steps " + std::to_string(job.steps) + ": the session was planned with " +
                       std::to_string(m.steps) + " steps");
  if (job.rig_given && job.rig != m.rig)
    throw InvalidInput("--rig " + job.rig + ": the session was recorded with the " + m.rig + " rig");
  if (job.object_given && job.object != m.object.name)
    throw InvalidInput("--object " + job.object + ": the session scans '" + m.object.name + "'");
  if (job.up_given && !sim::up_axis_rotation(job.up).isApprox(m.object.placement.rotation))
    throw InvalidInput("--up " + job.up + ": the session's object stands another way (its manifest's "
                       "object.placement.rotation)");
  // Other devices (a second laser, another camera format) would record steps
  // the manifest does not describe: laser1 frames in a one-laser session.
  const nlohmann::json* recorded = m.station.contains("fingerprint") ? &m.station["fingerprint"] : nullptr;
  const acquisition::StationFingerprint now = acquisition::station_fingerprint(job.station);
  if (recorded && recorded->value("hash", "") != now.hash)
    throw InvalidInput(job.folder.string() + ": the session was recorded with other devices than station '" + now.name +
                       "' (" + recorded->value("devices", nlohmann::json::object()).dump() + " against " +
                       now.devices.dump() + "); resume it with the station it was scanned with (--station)");
  if (job.parameters_given) context.log->warn("--resume keeps the session's parameters; replay to change them");
  return recorder;
}

std::string recorded_object(const acquisition::SessionManifest& m) {
  return m.object.mesh_file.empty() ? m.object.name : m.object.mesh_file;
}

// The simulated station's rig, laser or stereo, with the object on it.
struct SimulatedRig {
  std::optional<sim::SimulatedTurntable> laser;
  std::optional<sim::SimulatedStereo> stereo;
  const sim::ScanObject& object() const { return stereo ? stereo->object : laser->object; }
};

SimulatedRig simulated_rig(CommandContext& context, const ScanJob& job, const std::string& rig_name,
                           const std::string& object, const Eigen::Matrix3d& rotation, std::uint64_t seed) {
  SimulatedRig rig;
  const drivers::StationDescription& d = job.station;
  if (rig_name == "stereo") {
    rig.stereo.emplace(sim::simulated_stereo(sim::scan_object(object, rotation), d, seed));
    if (!d.projector)
      context.log->warn("{}: no [projector]: passive stereo, texture-less surfaces give few points",
                        d.source.empty() ? d.name : d.source.string());
  } else {
    rig.laser.emplace(sim::simulated_turntable(sim::scan_object(object, rotation), d, seed));
  }
  return rig;
}

// `rig`: the simulated rig, or none on a station with a real camera, whose
// geometry can only come from a calibration file and whose object is
// whatever stands on the platter (named by --object, in the platter's frame).
SessionRecorder create_session(CommandContext& context, const ScanJob& job, const SimulatedRig* rig) {
  acquisition::SessionManifest manifest;
  manifest.rig = job.rig;
  manifest.steps = job.steps;
  manifest.station = acquisition::station_json(job.station);
  if (rig) manifest.station["sim_seed"] = job.seed;
  const bool stereo = job.rig == "stereo";
  std::optional<acquisition::TurntableGeometry> truth;
  if (rig && rig->stereo) truth = acquisition::simulator_truth(rig->stereo->rig.left, {}, rig->stereo->rig.right);
  if (rig && rig->laser) truth = acquisition::simulator_truth(rig->laser->rig.camera, sim::light_planes(rig->laser->rig));
  manifest.geometry = acquisition::scan_geometry(
      job.calibration, job.station, truth, job.calibration_max_age,
      stereo ? acquisition::CalibrationNeed::stereo_pose : acquisition::CalibrationNeed::lasers);
  manifest.parameters = job.parameters;
  manifest.stereo_parameters = job.stereo_parameters;
  if (rig) {
    const sim::ScanObject& object = rig->object();
    manifest.object = {job.object, object.mesh_file, {object.scale, object.rotation, object.translation}};
  } else {
    manifest.object = {job.object_given ? job.object : "object", "", {}};
  }
  manifest.software_version = kVersion;
  return SessionRecorder::create(job.folder, manifest, context.overwrite);
}

// How the capture ran: what it recorded, and what stopped it early ("" when
// nothing did).
struct Capture {
  acquisition::RecordingOutcome outcome;
  std::string stopped_by;
  int signal = 0;
};

// Records the steps the session lacks on the simulated station's devices:
// `record` drives the opened station (laser or stereo rig), every recorded
// step goes to `on_step`.
using RigRecording = std::function<acquisition::RecordingOutcome(
    sim::OpenStation& station, const acquisition::RecordedStepSink& on_step, const std::function<bool()>& stop)>;

using StepFeed = std::function<void(int step, double angle_deg, const std::vector<acquisition::LaserScanPoints>&)>;

Capture record_on_devices(CommandContext& context, const ScanJob& job, SessionRecorder& recorder, unsigned roles,
                          const sim::FrameSourceFactory& frames, const sim::FrameSourceFactory& right_frames,
                          const RigRecording& record, const StepFeed& feed) {
  // Guarded before the first line is requested: a signal at any moment leaves
  // the station safe, and the capture stops after the step it is taking.
  sim::GuardedStation station(job.station, roles, frames, drivers::OnSignal::stop_work, right_frames);
  for (const auto& note : station->notes) context.log->warn("{}", note);
  const int steps = recorder.manifest().steps;
  StageTimer timer(context.report, "capture");
  const ProgressCallback progress = context.progress.stage("scan");
  Capture result;
  Eigen::Index points = 0;
  try {
    result.outcome = record(
        *station,
        [&](const acquisition::CapturedStep& step, const std::vector<acquisition::LaserScanPoints>& clouds) {
          for (const auto& cloud : clouds) points += cloud.cloud.size();
          context.progress.event("step", {{"step", step.step},
                                          {"angle_deg", step.angle_deg},
                                          {"steps_done", step.step + 1},
                                          {"steps", steps},
                                          {"points", points}});
          feed(step.step, step.angle_deg, clouds);
          if (progress) progress(double(step.step + 1) / steps);
        },
        [&] { return station.signal_received() != 0; });
  } catch (const std::exception& e) {
    // Whatever ended the capture (a signal cutting a move short, an unplugged
    // camera), the recorded steps are processed below.
    result.stopped_by = station.signal_received() ? "signal " + std::to_string(station.signal_received()) : e.what();
    result.outcome.steps_done = recorder.steps_done();
  }
  result.signal = station.signal_received();
  if (result.stopped_by.empty() && result.signal) result.stopped_by = "signal " + std::to_string(result.signal);
  context.progress.finish();
  timer.stop();
  station->make_safe();
  return result;
}

// Records the steps the session lacks with the rig's devices, each step's
// points to `feed`.
Capture capture(CommandContext& context, const ScanJob& job, SessionRecorder& recorder, const SimulatedRig* rig,
                const StepFeed& feed) {
  const drivers::StationDescription& d = job.station;
  const int stop_after = job.stop_after.value_or(0);
  if (recorder.manifest().rig == "stereo") {
    const unsigned roles = sim::camera_role | sim::right_camera_role | sim::turntable_role |
                           (d.projector ? sim::projector_role : 0u);
    return record_on_devices(
        context, job, recorder, roles, rig ? rig->stereo->left_frames : sim::FrameSourceFactory{},
        rig ? rig->stereo->right_frames : sim::FrameSourceFactory{},
        [&](sim::OpenStation& station, const auto& on_step, const auto& stop) {
          acquisition::StereoScanDevices devices{*station.camera,    *station.right_camera, station.projector.get(),
                                                 *station.turntable, *station.clock,        d.camera.timeout};
          return acquisition::record_stereo_session(devices, recorder, on_step, stop_after, stop);
        },
        feed);
  }
  return record_on_devices(
      context, job, recorder, sim::camera_role | sim::laser_role | sim::turntable_role,
      rig ? rig->laser->frames : sim::FrameSourceFactory{}, {},
      [&](sim::OpenStation& station, const auto& on_step, const auto& stop) {
        acquisition::TurntableScanDevices devices{*station.camera, {}, *station.turntable, *station.clock,
                                                  d.camera.timeout};
        for (auto& laser : station.lasers) devices.lasers.push_back(laser.get());
        return acquisition::record_turntable_session(devices, recorder, on_step, stop_after, stop);
      },
      feed);
}

std::string live_detail(const station::LiveStep& s, int steps) {
  return std::to_string(s.step + 1) + "/" + std::to_string(steps) + " steps, " + std::to_string(s.points) +
         " points, " + std::to_string(s.boundary_faces) + " boundary triangles";
}

}  // namespace

namespace {
bool simulated(const acquisition::SessionManifest& m) {
  return m.station.value("/camera/backend"_json_pointer, std::string()) == "sim";
}
}  // namespace

std::optional<TriangleMesh> known_object_surface(const acquisition::SessionManifest& m) {
  if (!simulated(m)) return std::nullopt;
  try {
    if (m.object.mesh_file.empty()) return sim::scan_object(m.object.name).on_platter;
    if (!std::filesystem::exists(m.object.mesh_file)) return std::nullopt;
    TriangleMesh mesh = io::read_mesh(m.object.mesh_file);
    if (mesh.face_count() == 0) return std::nullopt;
    return mesh;
  } catch (const InvalidInput&) {
    return std::nullopt;
  }
}

station::SessionProcessing session_processing(CommandContext& context, const acquisition::SessionManifest& manifest,
                                              std::optional<int> density) {
  station::SessionProcessing options;
  options.overwrite = io::Overwrite::replace;  // the command checked what it may replace
  options.density = density;
  options.truth = known_object_surface(manifest);
  // A simulated session whose mesh file moved lost its accuracy section
  // without a word (it was recorded relative to the folder scanned from).
  if (!options.truth && !manifest.object.mesh_file.empty() && simulated(manifest))
    context.log->warn("{}: the simulated object's mesh file is missing or has no faces: no accuracy against the "
                      "true surface",
                      manifest.object.mesh_file);
  options.live.camera_centre = manifest.geometry.camera.centre();  // lines of sight, as the replay's
  const int steps = manifest.steps;
  options.on_live_step = [&context, steps](const station::LiveStep& s) {
    context.progress.detail(live_detail(s, steps));
    context.progress.event("boundary", to_json(s));
  };
  return options;
}

void print_results(const nlohmann::json& r) {
  if (const long long thinned = r.value("points_thinned", 0LL); thinned > 0)
    std::printf("%lld points nearer than %g mm to a point kept before were dropped (--min-spacing)\n", thinned,
                r["parameters"]["min_spacing"].get<double>());
  // Two lasers: their agreement, when it holds or could not be told (a
  // disagreement is a warning of its own).
  if (const nlohmann::json& l = r.value("laser_agreement", nlohmann::json()); l.is_object()) {
    if (!l["checked"].get<bool>())
      std::printf("lasers 0 and 1 not compared: %s\n", l.value("reason", std::string()).c_str());
    else if (l["agree"].get<bool>())
      std::printf("lasers 0 and 1 agree: laser 0's cloud lies %.2g mm %s laser 1's (limit %.2g mm)\n",
                  std::abs(l["offset"].get<double>()), l["offset"].get<double>() > 0 ? "outside" : "inside",
                  l["resolution"].get<double>());
  }
  const nlohmann::json& b = r["boundary"];
  if (b.contains("error")) {
    std::printf("no boundary: %s\n", b["error"].get<std::string>().c_str());
  } else {
    std::printf("boundary: %lld triangles through %lld points, %s, genus %s, %s\n", b["faces"].get<long long>(),
                b["vertices"].get<long long>(), b["topology"]["closed"].get<bool>() ? "closed" : "OPEN",
                b["topology"]["genus"].dump().c_str(),
                b["all_on_boundary"].get<bool>() ? "every point on it" : "NOT every point on it");
  }
  if (r.contains("smoothing")) {
    const nlohmann::json& s = r["smoothing"];
    if (s.contains("error"))
      std::printf("smoothing failed: %s\n", s["error"].get<std::string>().c_str());
    else
      std::printf("smooth surface: %zu cubic patches (%s), largest normal angle across patch edges %.2g rad, "
                  "%.2g rad away from the %zu macro edges joined approximately (the sign condition fails at %zu "
                  "vertices)\n",
                  s["patches"].get<std::size_t>(), s["scheme"].get<std::string>().c_str(),
                  s["g1"]["max_normal_angle"].get<double>(), s["g1"]["max_normal_angle_where_exact"].get<double>(),
                  s["dependent_edges"].get<std::size_t>(), s["sign_condition_violations"].get<std::size_t>());
    print_fitted_positions(s);
    if (s.contains("flipped_faces") && !s["flipped_faces"].empty())
      std::printf("  on the boundary's triangles with %zu faces turned against their corners' normals flipped first\n",
                  s["flipped_faces"].size());
    if (const std::size_t folds = s["g1"].value("folded_edges", std::size_t{0}); folds > 0)
      std::printf("the smooth surface folds (normals turned apart) along %zu patch edge(s)\n", folds);
    if (s.contains("tessellation")) print_tessellation(s["tessellation"]);
  }
  if (r.contains("accuracy")) {
    const nlohmann::json& a = r["accuracy"];
    std::printf("against the true surface: points RMS %.3g (%.3f%% of the diagonal), mesh Hausdorff %.3g\n",
                a["points"]["rms"].get<double>(), 100 * a["points"]["rms_of_diagonal"].get<double>(),
                a["mesh"]["hausdorff"].get<double>());
    if (a.contains("seen")) {
      const nlohmann::json& seen = a["seen"];
      std::printf("  where the scan saw it (%.1f%% of the surface's area within %.3g of a point): mesh Hausdorff %.3g",
                  100 * seen["coverage"].get<double>(), seen["reach"].get<double>(),
                  seen["mesh"]["hausdorff"].get<double>());
      if (seen.contains("smooth")) std::printf(", smooth surface %.3g", seen["smooth"]["hausdorff"].get<double>());
      std::printf("\n");
    }
  }
  for (const auto& [name, path] : r["outputs"].items()) std::printf("  %-8s %s\n", name.c_str(), path.get<std::string>().c_str());
}

void run_scan_job(CommandContext& context, const ScanJob& job) {
  const drivers::StationDescription& description = job.station;
  std::optional<SessionRecorder> recorder;
  if (job.resume) recorder.emplace(resume_session(context, job));
  // A simulated camera renders the simulated object; a real one sees what
  // stands on the platter. A resumed scan simulates what the session
  // recorded, with its noise seed.
  std::optional<SimulatedRig> rig;
  if (job.up_given && description.camera.backend != "sim")
    throw InvalidInput("--up stands the simulated object on the platter; a real one stands as it was put there");
  if (description.camera.backend == "sim") {
    const std::string object = recorder ? recorded_object(recorder->manifest()) : job.object;
    const Eigen::Matrix3d rotation =
        recorder ? recorder->manifest().object.placement.rotation : sim::up_axis_rotation(job.up);
    const std::uint64_t seed = recorder ? recorder->manifest().station.value("sim_seed", job.seed) : job.seed;
    rig = simulated_rig(context, job, recorder ? recorder->manifest().rig : job.rig, object, rotation, seed);
  }
  if (!recorder) recorder.emplace(create_session(context, job, rig ? &*rig : nullptr));
  const acquisition::SessionManifest& manifest = recorder->manifest();
  for (const std::string& note : recorder->notes()) context.log->warn("{}", note);

  station::SessionProcessing processing = session_processing(context, manifest, job.density);
  processing.live.snapshot_every = job.snapshot_every;
  processing.live.snapshot_folder = job.folder / "snapshots";
  processing.live.placement = manifest.object.placement;
  processing.live.overwrite = io::Overwrite::replace;
  station::LiveBoundary live(processing.live);
  // The live boundary takes the points as the replay will: thinned to the
  // least spacing against every point fed before (the resumed steps come
  // thinned already, which thinning again leaves as they are).
  acquisition::SpacingFilter spacing(manifest.rig == "stereo" ? manifest.stereo_parameters.min_spacing
                                                              : manifest.parameters.min_spacing);
  const auto feed = [&](int step, double angle, std::vector<acquisition::LaserScanPoints> clouds) {
    for (acquisition::LaserScanPoints& cloud : clouds) spacing.thin(cloud);
    processing.on_live_step(live.add_step(step, angle, clouds));
  };
  if (recorder->steps_done() > 0) {  // resumed: the recorded steps first, so the live boundary holds them all
    StageTimer timer(context.report, "resume_replay");
    acquisition::ReplayOptions replay;
    replay.on_step = [&](int step, double angle, const auto& clouds, Eigen::Index) { feed(step, angle, clouds); };
    acquisition::replay_session(acquisition::read_session(job.folder), replay);
  }

  const Capture captured = capture(context, job, *recorder, rig ? &*rig : nullptr, feed);
  const acquisition::RecordingOutcome& outcome = captured.outcome;

  StageTimer process(context.report, "process");
  processing.replay.progress = context.progress.stage("process");
  processing.extra = {{"recorded_now", outcome.recorded_now}, {"live_boundary_seconds", live.seconds()}};
  if (!captured.stopped_by.empty())
    processing.extra["stopped"] = {{"by", captured.stopped_by}, {"after_steps", outcome.steps_done}};
  const nlohmann::json report =
      station::process_session(acquisition::read_session(job.folder), job.folder, processing, &live);
  context.progress.finish();
  process.stop();
  for (const std::string& warning : report.value("warnings", std::vector<std::string>{}))
    context.log->warn("{}", warning);
  for (const auto& key : {"rig", "steps", "complete", "points", "points_thinned", "points_per_laser", "problems", "object",
                          "laser_agreement", "boundary", "smoothing", "accuracy", "outputs", "stopped"})
    if (report.contains(key)) context.report[key] = report[key];
  context.report["session"] = job.folder.string();
  const bool complete = report["complete"].get<bool>();
  std::printf("%s %d of %d steps (%d now), %lld points\n", complete ? "scanned" : "stopped after",
              outcome.steps_done, manifest.steps, outcome.recorded_now, report["points"].get<long long>());
  print_results(report);
  if (!captured.stopped_by.empty()) {
    std::printf("stopped by %s; the session keeps every completed step\n", captured.stopped_by.c_str());
    context.exit_code = captured.signal ? 128 + captured.signal : 3;
  }
  if (!complete) std::printf("continue with: scanstation scan --resume -o %s\n", job.folder.c_str());
}

}  // namespace scanstation::app
