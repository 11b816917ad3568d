// scanstation replay: a recorded session processed again, with its own or new
// parameters and its recorded geometry or another calibration file, through
// the whole station flow (points, live boundary, smooth surface); the damage
// found is reported and what is intact is replayed.
#include "acquisition/scan_calibration.h"
#include "command.h"
#include "core/errors.h"
#include "scan_job.h"
#include "scan_parameter_options.h"

#include <cstdio>

namespace scanstation::app {

namespace {

class ReplayCommand final : public Command {
 public:
  explicit ReplayCommand(CLI::App& parent)
      : Command(parent, "replay", "Process a recorded scan session again (same or new parameters)") {
    cli_->add_option("session", session_, "Session folder written by 'scanstation scan'")->required();
    cli_->add_option("-o,--output", folder_, "Folder for the results (default: SESSION/replay)");
    cli_->add_option("--snapshot-every", snapshot_every_, "Write the live boundary as OUT/snapshots/boundary-step-NNNN.ply every K steps")
        ->check(CLI::Range(0, 100000));
    add_density_option(*cli_, density_);
    cli_->add_option("--calibration", calibration_,
                     "Triangulate with this station calibration file (e.g. a recalibration after the scan) instead "
                     "of the geometry the session recorded; refused when made for other devices, incomplete or stale");
    cli_->add_option("--calibration-max-age", calibration_max_age_,
                     "With --calibration: refuse a calibration whose oldest part is older than this (days; 0: any age)")
        ->check(finite_range(0.0, 1e6))
        ->capture_default_str();
    parameters_.add_to(*cli_);
    spacing_.add_to(*cli_);
    stereo_.add_to(*cli_);
  }

  bool makes_output_folder() const override { return true; }

  void run(CommandContext& context) override {
    const std::filesystem::path out = folder_.empty() ? session_ / "replay" : folder_;
    for (const char* name : station::kResultFiles) io::check_writable(out / name, context.overwrite);
    const acquisition::SessionContents contents = acquisition::read_session(session_);
    // Damage is reported and what is intact replayed; a session with nothing
    // intact is an error, not an empty result.
    const auto nothing = [&](const std::string& why) {
      for (const std::string& problem : contents.problems) context.log->warn("{}", problem);
      return InvalidInput(session_.string() + ": nothing to replay: " + why);
    };
    if (contents.steps.empty()) throw nothing("no complete step is recorded in its journal");
    if (contents.manifest.rig == "turntable" && contents.lasers.empty() && calibration_.empty())
      throw nothing("no laser plane of its geometry is intact (replay with --calibration FILE to use another)");
    station::SessionProcessing processing = session_processing(context, contents.manifest, density_);
    const bool stereo = contents.manifest.rig == "stereo";
    if (parameters_.any() || (spacing_.min_spacing && !stereo))
      processing.replay.parameters = spacing_.apply(parameters_.apply(contents.manifest.parameters));
    if (!stereo_.given().empty() || (spacing_.min_spacing && stereo))
      processing.replay.stereo_parameters = spacing_.apply(stereo_.apply(contents.manifest.stereo_parameters));
    if (!calibration_.empty())
      processing.replay.geometry = acquisition::replay_geometry(calibration_, contents, calibration_max_age_);
    processing.replay.progress = context.progress.stage("replay");
    processing.live.snapshot_every = snapshot_every_;
    processing.live.snapshot_folder = out / "snapshots";
    processing.live.overwrite = context.overwrite;
    processing.extra = {{"replay_of", session_.string()}};
    const nlohmann::json report = station::process_session(contents, out, processing);
    context.progress.finish();
    for (const auto& problem : report["problems"]) context.log->warn("{}", problem.get<std::string>());
    if (report["steps"]["used"].get<int>() == 0)
      throw InvalidInput(session_.string() + ": nothing to replay: none of its " +
                         std::to_string(contents.steps.size()) + " recorded steps could be used (see the warnings)");
    for (const std::string& warning : report.value("warnings", std::vector<std::string>{}))
      context.log->warn("{}", warning);
    for (const auto& key : {"steps", "complete", "points", "points_thinned", "points_per_laser", "problems",
                            "replay_speedup", "geometry",
                            "laser_agreement", "boundary", "smoothing", "accuracy", "outputs"})
      if (report.contains(key)) context.report[key] = report[key];
    const auto& seconds = report["seconds"];
    std::printf("replayed %d of %zu recorded steps (%d planned), %lld points in %.2f s; the capture took %.1f s\n",
                report["steps"]["used"].get<int>(), contents.steps.size(), contents.manifest.steps,
                report["points"].get<long long>(), seconds["processing"].get<double>(),
                seconds["capture"].get<double>());
    const std::string source = report["geometry_source"].get<std::string>();
    std::printf("geometry: %s\n", report["geometry"]["recorded"].get<bool>() ? ("as recorded: " + source).c_str()
                                                                             : source.c_str());
    print_results(report);
    if (!report["problems"].empty())
      std::printf("%zu problem(s) found; what is intact was replayed (see the warnings and report.json)\n",
                  report["problems"].size());
  }

 private:
  std::filesystem::path session_;
  std::filesystem::path folder_;
  int snapshot_every_ = 0;
  std::optional<int> density_;  // none: automatic
  std::filesystem::path calibration_;
  double calibration_max_age_ = acquisition::kCalibrationMaxAgeDays;
  ScanParameterOptions parameters_;
  SpacingOption spacing_;
  StereoParameterOptions stereo_;
};

}  // namespace

std::unique_ptr<Command> make_replay_command(CLI::App& parent) { return std::make_unique<ReplayCommand>(parent); }

}  // namespace scanstation::app
