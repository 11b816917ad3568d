// Processing a recorded session into points: the scan command does it on the
// session it has just recorded, the replay command on any session, with the
// recorded or new parameters. Same session and parameters → the same
// points.ply, byte for byte.
#pragma once

#include "acquisition/laser_agreement.h"
#include "acquisition/session.h"
#include "acquisition/stereo_scan_parameters.h"
#include "acquisition/turntable_step_points.h"
#include "core/progress.h"

#include <functional>
#include <optional>

namespace scanstation::acquisition {

/// parameters  replaces the recorded processing parameters (laser session)
/// stereo_parameters  replaces them for a stereo session
/// geometry    replaces the recorded geometry (another calibration, on purpose)
/// on_step     called after each recorded step with its index, angle, its
///             points (one cloud per laser, platter object frame; empty when
///             its frames are unusable) and the number of points so far —
///             a replay feeds a live view or an incremental reconstruction
///             batch by batch, as the scan does
struct ReplayOptions {
  std::optional<LaserScanParameters> parameters;
  std::optional<StereoScanParameters> stereo_parameters;
  std::optional<TurntableGeometry> geometry;
  ProgressCallback progress;
  std::function<void(int step, double angle_deg, const std::vector<LaserScanPoints>& step_points,
                     Eigen::Index points_so_far)>
      on_step;
};

/// points            the scan in the object's own coordinates (the mesh file's
///                   for a simulated mesh), step by step, laser by laser
/// by_laser          each laser's points in the platter's object frame, before
///                   the least spacing (it would thin one laser's by the other's)
/// points_thinned    points dropped for the least spacing (min_spacing)
/// steps_used        steps that gave frames to process
/// problems          the session's damage (read_session) and every frame
///                   that could not be used, each naming its file
/// laser_agreement   with two lasers: the distance between their clouds
///                   (check_laser_agreement over the planned steps per turn)
/// fed_index         with outliers removed: for every point, its index among
///                   the points processed (on_step order); else empty
/// geometry          the geometry the points were triangulated with: the
///                   recorded one (recorded_geometry) or ReplayOptions::geometry
/// capture_seconds   the recorded steps' own duration (move start to last frame)
/// process_seconds   wall time of the processing
struct ScanResult {
  LaserScanPoints points;
  std::vector<LaserScanPoints> by_laser;
  int steps_used = 0;
  Eigen::Index points_thinned = 0;
  Eigen::Index outliers_removed = 0;
  std::vector<Eigen::Index> fed_index;
  LaserScanParameters parameters;
  StereoScanParameters stereo_parameters;
  TurntableGeometry geometry;
  bool recorded_geometry = true;
  std::vector<std::string> problems;
  std::optional<LaserAgreementCheck> laser_agreement;
  double capture_seconds = 0, process_seconds = 0;
};

/// Processes every recorded step of `session` (missing or unreadable frames
/// skip their laser, or the step for a laser-off frame, with a problem
/// noted), thinning each step's points to the parameters' least spacing
/// as they come (on_step sees them thinned), then removes outliers if the parameters ask for it and turns the
/// points into the object's own coordinates (manifest object.placement).
ScanResult replay_session(const SessionContents& session, const ReplayOptions& options = {});

/// A frame of a session as recorded (8 or 16 bit; an alpha channel is dropped);
/// empty if missing or unreadable.
cv::Mat read_session_frame(const std::filesystem::path& file);

/// The warning to print when the scan's two lasers disagree (laser_disagreement_message), else nullopt.
std::optional<std::string> laser_agreement_warning(const ScanResult& result);

/// Writes `folder`/points.ply (binary, with colours) and `folder`/report.json:
/// session, steps planned/recorded/used, points per laser, outliers, the
/// geometry used ("geometry_source", and "geometry": {"source", "recorded",
/// "calibration"}), the parameters, problems, laser agreement (null with one laser), capture and
/// processing seconds and their ratio.
/// `extra` is merged into the report. Returns the report.
nlohmann::json write_scan_results(const std::filesystem::path& folder, const SessionContents& session,
                                  const ScanResult& result, const nlohmann::json& extra, io::Overwrite overwrite);

}  // namespace scanstation::acquisition
