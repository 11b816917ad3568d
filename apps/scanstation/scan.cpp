// scanstation scan: a turntable laser scan recorded into a session folder
// (acquisition/session.h), then processed into points.ply and report.json.
#include "acquisition/scan_calibration.h"
#include "acquisition/session_recording.h"
#include "acquisition/session_replay.h"
#include "command.h"
#include "core/errors.h"
#include "core/version.h"
#include "scan_parameter_options.h"
#include "sim/simulated_turntable.h"
#include "station_options.h"

#include <cstdio>

namespace scanstation::app {

namespace {

using acquisition::SessionRecorder;

class ScanCommand final : public Command {
 public:
  explicit ScanCommand(CLI::App& parent)
      : Command(parent, "scan", "Scan an object on the turntable into a session folder (frames, journal, points)") {
    cli_->add_option("--rig", rig_, "turntable (one camera, line lasers) or stereo")
        ->check(CLI::IsMember({"turntable", "stereo"}))
        ->capture_default_str();
    station_.add_to(*cli_);
    cli_->add_option("--object", object_,
                     "Simulated object: sphere, ellipsoid, torus, chalice, candlestick or a mesh file (placed and "
                     "scaled to fit the rig; points.ply comes out in the file's own coordinates)")
        ->capture_default_str();
    cli_->add_option("--steps", steps_, "Turntable steps per turn")->check(CLI::Range(1, 100000))->capture_default_str();
    cli_->add_flag("--resume", resume_, "Continue the interrupted session in -o after its last recorded step");
    cli_->add_option("--stop-after", stop_after_, "Record at most this many steps now (the session stays resumable)")
        ->check(CLI::Range(1, 100000));
    cli_->add_option("--seed", seed_, "Seed of the simulated sensor noise")->capture_default_str();
    cli_->add_option("-o,--output", folder_, "Session folder")->required();
    // Calibration (acquisition/scan_calibration.h): which geometry the scan triangulates with.
    cli_->add_option("--calibration", calibration_,
                     "Station calibration file (default: the one the station description names; on the simulator "
                     "without one, or with 'sim-truth', the simulator's true geometry)");
    cli_->add_option("--calibration-max-age", calibration_max_age_,
                     "Refuse a calibration whose oldest part is older than this (days; 0: any age)")
        ->check(CLI::NonNegativeNumber)
        ->capture_default_str();
    parameters_.add_to(*cli_);
  }

  void run(CommandContext& context) override {
    if (rig_ == "stereo")
      throw InvalidInput("--rig stereo: not yet supported (the stereo capture pipeline is being built); use "
                         "--rig turntable");
    const drivers::StationDescription description = station_.description();
    if (description.camera.backend != "sim")
      throw InvalidInput("scan: the scan drives simulated devices only (real stations are being wired); scan on "
                         "the simulator with --backend sim");
    std::optional<SessionRecorder> recorder;
    if (resume_) recorder.emplace(resume_session(context));
    // A resumed scan simulates what the session recorded, with its noise seed.
    const std::string object = recorder ? recorded_object(recorder->manifest()) : object_;
    if (recorder) seed_ = recorder->manifest().station.value("sim_seed", seed_);
    const sim::SimulatedTurntable simulated = sim::simulated_turntable(sim::scan_object(object), description, seed_);
    if (!recorder) recorder.emplace(create_session(context, description, simulated));
    const acquisition::SessionManifest& manifest = recorder->manifest();
    for (const std::string& note : recorder->notes()) context.log->warn("{}", note);

    // Guarded before the first line is requested: a signal at any moment leaves the station safe.
    sim::GuardedStation station(description, sim::camera_role | sim::laser_role | sim::turntable_role,
                                simulated.frames);
    for (const auto& note : station->notes) context.log->warn("{}", note);
    acquisition::TurntableScanDevices devices{*station->camera, {}, *station->turntable, *station->clock,
                                              description.camera.timeout};
    for (auto& laser : station->lasers) devices.lasers.push_back(laser.get());

    StageTimer capture(context.report, "capture");
    const ProgressCallback progress = context.progress.stage("scan");
    Eigen::Index live_points = 0;
    const auto outcome = acquisition::record_turntable_session(
        devices, *recorder,
        [&](const acquisition::CapturedStep& step, const std::vector<acquisition::LaserScanPoints>& clouds) {
          for (const auto& cloud : clouds) live_points += cloud.cloud.size();
          context.progress.detail(std::to_string(step.step + 1) + "/" + std::to_string(manifest.steps) + " steps, " +
                                  std::to_string(live_points) + " points");
          if (progress) progress(double(step.step + 1) / manifest.steps);
          context.progress.event("step", {{"step", step.step},
                                          {"angle_deg", step.angle_deg},
                                          {"steps_done", step.step + 1},
                                          {"steps", manifest.steps},
                                          {"points", live_points}});
        },
        stop_after_.value_or(0));
    context.progress.finish();
    capture.stop();
    station->make_safe();

    StageTimer process(context.report, "process");
    const acquisition::SessionContents contents = acquisition::read_session(folder_);
    const acquisition::ScanResult result = acquisition::replay_session(contents);
    const nlohmann::json report = acquisition::write_scan_results(
        folder_, contents, result, {{"recorded_now", outcome.recorded_now}}, io::Overwrite::replace);
    process.stop();
    for (const auto& key : {"steps", "complete", "points", "points_per_laser", "problems", "object", "laser_agreement"})
      context.report[key] = report[key];
    if (const auto warning = acquisition::laser_agreement_warning(result)) context.log->warn("{}", *warning);
    context.report["session"] = folder_.string();
    std::printf("%s %d of %d steps (%d now), %lld points: %s\n", outcome.complete ? "scanned" : "stopped after",
                outcome.steps_done, manifest.steps, outcome.recorded_now,
                static_cast<long long>(result.points.cloud.size()), (folder_ / "points.ply").c_str());
    if (!outcome.complete) std::printf("continue with: scanstation scan --resume -o %s\n", folder_.c_str());
  }

 private:
  SessionRecorder resume_session(CommandContext& context) const {
    SessionRecorder recorder = SessionRecorder::resume(folder_);
    const auto& m = recorder.manifest();
    if (cli_->count("--steps") && steps_ != m.steps)
      throw InvalidInput("--steps " + std::to_string(steps_) + ": the session was planned with " +
                         std::to_string(m.steps) + " steps");
    if (cli_->count("--object") && object_ != m.object.name)
      throw InvalidInput("--object " + object_ + ": the session scans '" + m.object.name + "'");
    if (parameters_.any()) context.log->warn("--resume keeps the session's parameters; replay to change them");
    return recorder;
  }

  static std::string recorded_object(const acquisition::SessionManifest& m) {
    return m.object.mesh_file.empty() ? m.object.name : m.object.mesh_file;
  }

  SessionRecorder create_session(CommandContext& context, const drivers::StationDescription& description,
                                 const sim::SimulatedTurntable& simulated) const {
    acquisition::SessionManifest manifest;
    manifest.rig = rig_;
    manifest.steps = steps_;
    manifest.station = acquisition::station_json(description);
    manifest.station["sim_seed"] = seed_;
    manifest.geometry = acquisition::scan_geometry(calibration_, description, sim::truth_geometry(simulated.rig),
                                                   calibration_max_age_);
    manifest.parameters = parameters_.apply({});
    manifest.object = {object_, simulated.object.mesh_file, {simulated.object.scale, simulated.object.translation}};
    manifest.software_version = kVersion;
    return SessionRecorder::create(folder_, manifest, context.overwrite);
  }

  std::string rig_ = "turntable";
  StationOptions station_;
  std::string object_ = "sphere";
  int steps_ = 36;
  bool resume_ = false;
  std::optional<int> stop_after_;
  std::uint64_t seed_ = 1;
  std::filesystem::path folder_;
  ScanParameterOptions parameters_;
  std::string calibration_;
  double calibration_max_age_ = acquisition::kCalibrationMaxAgeDays;
};

}  // namespace

std::unique_ptr<Command> make_scan_command(CLI::App& parent) { return std::make_unique<ScanCommand>(parent); }

}  // namespace scanstation::app
