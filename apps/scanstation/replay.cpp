// scanstation replay: a recorded session processed again, with its own or new
// parameters; the damage found is reported and what is intact is replayed.
#include "acquisition/session_replay.h"
#include "command.h"
#include "scan_parameter_options.h"

#include <cstdio>

namespace scanstation::app {

namespace {

class ReplayCommand final : public Command {
 public:
  explicit ReplayCommand(CLI::App& parent)
      : Command(parent, "replay", "Process a recorded scan session again (same or new parameters)") {
    cli_->add_option("session", session_, "Session folder written by 'scanstation scan'")->required();
    cli_->add_option("-o,--output", folder_, "Folder for points.ply and report.json (default: SESSION/replay)");
    parameters_.add_to(*cli_);
  }

  void run(CommandContext& context) override {
    const std::filesystem::path out = folder_.empty() ? session_ / "replay" : folder_;
    for (const char* name : {"points.ply", "report.json"}) io::check_writable(out / name, context.overwrite);
    const acquisition::SessionContents contents = acquisition::read_session(session_);
    acquisition::ReplayOptions options;
    if (parameters_.any()) options.parameters = parameters_.apply(contents.manifest.parameters);
    options.progress = context.progress.stage("replay");
    options.on_step = [&](int step, double angle, const std::vector<acquisition::LaserScanPoints>&,
                          Eigen::Index points) {
      context.progress.detail(std::to_string(points) + " points");
      context.progress.event("step", {{"step", step}, {"angle_deg", angle}, {"points", points}});
    };
    const acquisition::ScanResult result = acquisition::replay_session(contents, options);
    context.progress.finish();
    for (const std::string& problem : result.problems) context.log->warn("{}", problem);
    const nlohmann::json report =
        acquisition::write_scan_results(out, contents, result, {{"replay_of", session_.string()}}, context.overwrite);
    context.report.add_seconds("process", result.process_seconds);
    for (const auto& key : {"steps", "complete", "points", "points_per_laser", "problems", "replay_speedup"})
      context.report[key] = report[key];
    std::printf("replayed %d of %zu recorded steps (%d planned), %lld points in %.2f s; the capture took %.1f s "
                "(%.0fx faster): %s\n",
                result.steps_used, contents.steps.size(), contents.manifest.steps,
                static_cast<long long>(result.points.cloud.size()), result.process_seconds, result.capture_seconds,
                result.process_seconds > 0 ? result.capture_seconds / result.process_seconds : 0.0,
                (out / "points.ply").c_str());
    if (!result.problems.empty())
      std::printf("%zu problem(s) found; what is intact was replayed (see the warnings and report.json)\n",
                  result.problems.size());
  }

 private:
  std::filesystem::path session_;
  std::filesystem::path folder_;
  ScanParameterOptions parameters_;
};

}  // namespace

std::unique_ptr<Command> make_replay_command(CLI::App& parent) { return std::make_unique<ReplayCommand>(parent); }

}  // namespace scanstation::app
