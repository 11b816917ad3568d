// scanstation scan: a turntable scan (laser or stereo rig) recorded into a session folder
// (acquisition/session.h) with the boundary grown live, then processed into
// points.ply, mesh.ply, smooth.ply, patches.json, preview.png and report.json.
#include "command.h"
#include "acquisition/session.h"
#include "core/errors.h"
#include "drivers/station_description.h"
#include "scan_job.h"
#include "scan_parameter_options.h"
#include "station_options.h"

#include <optional>

namespace scanstation::app {

namespace {

class ScanCommand final : public Command {
 public:
  explicit ScanCommand(CLI::App& parent)
      : Command(parent, "scan",
                "Scan an object on the turntable into a session folder: frames, journal, points, the closed boundary "
                "grown live, the smooth surface") {
    cli_->add_option("--rig", rig_,
                     "turntable (one camera, line lasers) or stereo (two cameras and a random-dot projector; the "
                     "station needs [right_camera], default: the built-in simulated stereo station)")
        ->check(CLI::IsMember({"turntable", "stereo"}))
        ->capture_default_str();
    station_.add_to(*cli_);
    cli_->add_option("--object", job_.object,
                     "Simulated object: sphere, ellipsoid, torus, chalice, candlestick or a mesh file (placed and "
                     "scaled to fit the rig; the results come out in the file's own coordinates)")
        ->capture_default_str();
    add_up_option(*cli_, job_.up);
    cli_->add_option("--steps", job_.steps, "Turntable steps per turn")->check(CLI::Range(1, 100000))->capture_default_str();
    cli_->add_flag("--resume", job_.resume, "Continue the interrupted session in -o after its last recorded step");
    cli_->add_option("--stop-after", job_.stop_after, "Record at most this many steps now (the session stays resumable)")
        ->check(CLI::Range(1, 100000));
    cli_->add_option("--seed", job_.seed, "Seed of the simulated sensor noise")
        ->check(non_negative_integer())
        ->capture_default_str();
    cli_->add_option("--snapshot-every", job_.snapshot_every,
                     "Write the live boundary as SESSION/snapshots/boundary-step-NNNN.ply every K steps")
        ->check(CLI::Range(0, 100000));
    add_density_option(*cli_, job_.density);
    cli_->add_option("-o,--output", job_.folder, "Session folder (the results are written into it too)")->required();
    // Calibration (acquisition/scan_calibration.h): which geometry the scan triangulates with.
    cli_->add_option("--calibration", job_.calibration,
                     "Station calibration file (default: the one the station description names; on the simulator "
                     "without one, or with 'sim-truth', the simulator's true geometry)");
    cli_->add_option("--calibration-max-age", job_.calibration_max_age,
                     "Refuse a calibration whose oldest part is older than this (days; 0: any age)")
        ->check(finite_range(0.0, 1e6))
        ->capture_default_str();
    parameters_.add_to(*cli_);
    spacing_.add_to(*cli_);
    stereo_.add_to(*cli_);
    cli_->footer("With --progress=json, every step emits a \"step\" event and a \"boundary\" event (points so far, "
                 "boundary triangles, all_on_boundary). Ctrl-C stops after the current step and still writes the "
                 "results; --resume continues.");
  }

  bool makes_output_folder() const override { return true; }

  void run(CommandContext& context) override {
    // A resumed scan continues with the session's own rig.
    job_.rig_given = cli_->count("--rig") > 0;
    const std::optional<acquisition::SessionManifest> resumed =
        job_.resume ? std::optional(acquisition::read_session(job_.folder).manifest) : std::nullopt;
    job_.rig = resumed && !job_.rig_given ? resumed->rig : rig_;
    if (job_.rig == "stereo" && parameters_.any())
      throw InvalidInput("--rig stereo: the laser processing options (--peak-fit, --row-step, ...) do not apply");
    if (job_.rig != "stereo" && !stereo_.given().empty())
      throw InvalidInput(stereo_.given() + ": a stereo option; the laser rig takes --row-step and the other laser "
                         "processing options");
    job_.parameters_given = parameters_.any() || !stereo_.given().empty() || spacing_.min_spacing;
    // Without --station the built-in simulated station of the rig.
    job_.station = job_.rig == "stereo" && station_.station.empty() ? drivers::simulated_stereo_station()
                                                                    : station_.description();
    // A session of the built-in laser station resumes with the lasers it was
    // scanned with: the built-in station had one before it had two.
    if (resumed && station_.station.empty() && job_.rig != "stereo") {
      const nlohmann::json& recorded = resumed->station;
      const nlohmann::json lasers = recorded.value("/fingerprint/devices/lasers"_json_pointer, nlohmann::json());
      if (recorded.value("file", std::string()).empty() && lasers.is_array() && !lasers.empty())
        job_.station.lasers.assign(lasers.size(), drivers::LaserRole{});
    }
    job_.steps_given = cli_->count("--steps") > 0;
    job_.object_given = cli_->count("--object") > 0;
    job_.up_given = cli_->count("--up") > 0;
    job_.parameters = spacing_.apply(parameters_.apply({}));
    job_.stereo_parameters = spacing_.apply(stereo_.apply(acquisition::stereo_scan_defaults()));
    run_scan_job(context, job_);
  }

 private:
  std::string rig_ = "turntable";
  StationOptions station_;
  ScanJob job_;
  ScanParameterOptions parameters_;
  SpacingOption spacing_;
  StereoParameterOptions stereo_;
};

}  // namespace

std::unique_ptr<Command> make_scan_command(CLI::App& parent) { return std::make_unique<ScanCommand>(parent); }

}  // namespace scanstation::app
