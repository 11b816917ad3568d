// The station flow as the commands run it (issue 8): a turntable scan (laser
// or stereo rig) recorded into a session with the boundary grown live, then
// processed into the results. `scan` and `demo` run a ScanJob; `replay` runs the processing
// alone.
#pragma once

#include "acquisition/scan_calibration.h"
#include "acquisition/session.h"
#include "command.h"
#include "drivers/station_description.h"
#include "station/session_processing.h"

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

namespace scanstation::app {

/// rig             "turntable" (camera and line lasers) or "stereo" (two
///                 cameras and a projector: the station needs [right_camera])
/// object          simulated object: built-in name or mesh file
/// up              which of the mesh file's axes points up (sim::up_axis_rotation)
/// parameters      laser processing parameters (a resumed session keeps its own)
/// stereo_parameters  the stereo rig's (likewise)
/// snapshot_every  K > 0: the live boundary as PLY every K steps into folder/snapshots
/// calibration     see acquisition::scan_geometry
struct ScanJob {
  std::string rig = "turntable";
  drivers::StationDescription station;
  std::string object = "sphere";
  std::string up = "z";
  int steps = 36;
  bool resume = false;
  bool rig_given = false, steps_given = false, object_given = false, up_given = false, parameters_given = false;
  std::optional<int> stop_after;
  std::uint64_t seed = 1;
  std::filesystem::path folder;
  acquisition::LaserScanParameters parameters;
  acquisition::StereoScanParameters stereo_parameters = acquisition::stereo_scan_defaults();
  int snapshot_every = 0;
  std::optional<int> density;  ///< smooth.ply's segments per patch edge; none: automatic
  std::string calibration;  ///< file, "sim-truth", or "" (the station's, else the simulator's truth)
  double calibration_max_age = acquisition::kCalibrationMaxAgeDays;
};

/// Records (or resumes) the session in job.folder, growing the boundary live
/// (progress events "step" and "boundary"), then writes the results there.
/// Ctrl-C/SIGTERM or a device error ends the capture after the last complete
/// step: the results of what was recorded are written, the report says where
/// it stopped, and context.exit_code is set (128 + signal, or 3).
void run_scan_job(CommandContext& context, const ScanJob& job);

/// The processing options every command shares: progress, live events,
/// the known object's true surface for a simulated session.
station::SessionProcessing session_processing(CommandContext& context, const acquisition::SessionManifest& manifest,
                                              std::optional<int> density);

/// The true surface of a simulated session's object in its own coordinates
/// (the built-in shape, or the mesh file as recorded when it is still
/// there); nothing for a real scan.
std::optional<TriangleMesh> known_object_surface(const acquisition::SessionManifest& manifest);

/// Prints the summary lines of a processed session.
void print_results(const nlohmann::json& report);

}  // namespace scanstation::app
