#include "acquisition/session_replay.h"

#include "acquisition/outlier_removal.h"
#include "acquisition/point_spacing.h"
#include "acquisition/stereo_step_points.h"
#include "core/errors.h"
#include "core/image_codecs.h"
#include "core/io/file_access.h"
#include "core/io/mesh_io.h"
#include "core/version.h"

#include <chrono>
#include <opencv2/imgproc.hpp>

namespace scanstation::acquisition {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// Why a decoded frame cannot stand for `camera`'s (empty when it can): the
// size must be the camera's, the pixels grey (8 or 16 bits) or 8-bit colour,
// as the station records them. Such a frame is skipped like an unreadable
// one, not the whole replay refused.
std::string frame_mismatch(const cv::Mat& frame, const PinholeCamera& camera) {
  if (frame.cols != camera.width || frame.rows != camera.height)
    return "a " + std::to_string(frame.cols) + "x" + std::to_string(frame.rows) + " image, not the camera's " +
           std::to_string(camera.width) + "x" + std::to_string(camera.height);
  if (frame.type() != CV_8UC1 && frame.type() != CV_16UC1 && frame.type() != CV_8UC3)
    return "pixels of " + std::to_string(frame.channels()) + " channel(s) of " +
           std::to_string(8 * frame.elemSize1()) + " bits, not 8- or 16-bit grey or 8-bit colour";
  return {};
}

// The frame at `path` when it can stand for `camera`'s, else empty with
// `why` saying what is wrong: missing, unreadable, or a frame_mismatch.
cv::Mat usable_frame(const fs::path& path, const PinholeCamera& camera, std::string& why) {
  std::error_code error;  // a symbolic link loop, a folder without access: said like a missing frame
  const fs::file_status status = fs::status(path, error);
  if (error || !fs::is_regular_file(status)) {
    why = !error ? (fs::exists(status) ? "not a file" : "missing")
                 : error == std::errc::no_such_file_or_directory ? "missing" : "unreadable (" + error.message() + ")";
    return {};
  }
  cv::Mat frame = read_session_frame(path);
  why = frame.empty() ? "unreadable" : frame_mismatch(frame, camera);
  return why.empty() ? frame : cv::Mat();
}

// The frames of one step that can be used, with a problem noted for each
// that cannot. No laser-off frame → no frames at all.
std::optional<StepFrames> load_step(const SessionContents& session, const SessionStep& step,
                                    const std::vector<int>& lasers, std::vector<std::string>& problems) {
  StepFrames frames;
  frames.angle_deg = step.angle_deg;
  // The frame, or empty with a problem noted saying what happens instead.
  const auto load = [&](const SessionFrame& f, const std::string& consequence) {
    const fs::path path = session.folder / f.file;
    std::string why;
    cv::Mat frame = usable_frame(path, session.manifest.geometry.camera, why);
    if (frame.empty())
      problems.push_back(path.string() + ": " + why + " (journal line " + std::to_string(step.journal_line) +
                         "): " + consequence);
    return frame;
  };
  const auto off = std::find_if(step.frames.begin(), step.frames.end(), [](const SessionFrame& f) { return !f.laser; });
  const std::string step_name = "step " + std::to_string(step.step);
  if (off == step.frames.end()) {
    problems.push_back("journal line " + std::to_string(step.journal_line) + ": " + step_name +
                       " has no laser-off frame: step skipped");
    return std::nullopt;
  }
  frames.off = load(*off, step_name + " skipped");
  if (frames.off.empty()) return std::nullopt;
  for (const SessionFrame& f : step.frames) {
    if (!f.laser || std::find(lasers.begin(), lasers.end(), *f.laser) == lasers.end()) continue;
    cv::Mat on = load(f, step_name + " laser " + std::to_string(*f.laser) + " skipped");
    if (!on.empty()) frames.on.emplace_back(*f.laser, std::move(on));
  }
  return frames;
}

// The pair and colour frame of a stereo step, with a problem noted for each
// that cannot be used. No pair → no frames at all.
std::optional<StereoStepFrames> load_stereo_step(const SessionContents& session, const SessionStep& step,
                                                 std::vector<std::string>& problems) {
  const StereoFrameRoles roles = stereo_frame_roles(step.frames);
  const std::string step_name = "step " + std::to_string(step.step);
  const std::string line = " (journal line " + std::to_string(step.journal_line) + ")";
  if (roles.left < 0 || roles.right < 0) {
    problems.push_back("journal line " + std::to_string(step.journal_line) + ": " + step_name +
                       " lacks the " + (roles.left < 0 ? "left" : "right") + " frame of its pair: step skipped");
    return std::nullopt;
  }
  // A frame, or empty with a problem noted saying what happens instead.
  const TurntableGeometry& geometry = session.manifest.geometry;
  const auto load = [&](int index, const std::string& consequence) {
    const SessionFrame& f = step.frames[static_cast<std::size_t>(index)];
    const fs::path path = session.folder / f.file;
    std::string why;
    cv::Mat frame =
        usable_frame(path, f.camera == 0 || !geometry.right_camera ? geometry.camera : *geometry.right_camera, why);
    if (frame.empty()) problems.push_back(path.string() + ": " + why + line + ": " + consequence);
    return frame;
  };
  StereoStepFrames frames;
  frames.angle_deg = step.angle_deg;
  frames.left = load(roles.left, step_name + " skipped");
  if (frames.left.empty()) return std::nullopt;
  frames.right = load(roles.right, step_name + " skipped");
  if (frames.right.empty()) return std::nullopt;
  if (roles.colour >= 0) frames.colour = load(roles.colour, step_name + " coloured from its pair");
  return frames;
}

}  // namespace

cv::Mat read_session_frame(const fs::path& file) {
  cv::Mat frame;
  try {
    frame = image::read(file.string(), cv::IMREAD_UNCHANGED);
  } catch (const cv::Exception&) {  // a header beyond OpenCV's limits: unreadable, as any other
    return {};
  }
  // An image editor may save a frame with an alpha channel: the colour is the frame.
  if (frame.type() == CV_8UC4) cv::cvtColor(frame, frame, cv::COLOR_BGRA2BGR);
  return frame;
}

ScanResult replay_session(const SessionContents& session, const ReplayOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const SessionManifest& manifest = session.manifest;
  const bool stereo = manifest.rig == "stereo";
  if (stereo && options.parameters)
    throw InvalidInput((session.folder / "manifest.json").string() +
                       ": a stereo session: the laser processing parameters do not apply to it (it is replayed "
                       "with the stereo options: --block-size, --num-disparities, --uniqueness, --pixel-step)");
  if (!stereo && options.stereo_parameters)
    throw InvalidInput((session.folder / "manifest.json").string() + ": a " + manifest.rig +
                       " session: the stereo options do not apply to it (it takes the laser processing options)");
  ScanResult result;
  result.problems = session.problems;
  result.parameters = options.parameters.value_or(manifest.parameters);
  result.stereo_parameters = options.stereo_parameters.value_or(manifest.stereo_parameters);
  result.geometry = options.geometry.value_or(manifest.geometry);
  result.recorded_geometry = !options.geometry;
  const TurntableGeometry& geometry = result.geometry;
  std::vector<int> lasers = session.lasers;
  if (options.geometry) {
    lasers.clear();
    for (std::size_t i = 0; i < geometry.lasers.size(); ++i) lasers.push_back(static_cast<int>(i));
  }
  std::optional<StereoScanSetup> stereo_setup;
  if (stereo) stereo_setup = stereo_scan_setup(geometry, result.stereo_parameters);
  result.by_laser.resize(stereo ? 1 : geometry.lasers.size());
  SpacingFilter spacing(stereo ? result.stereo_parameters.min_spacing : result.parameters.min_spacing);
  for (std::size_t s = 0; s < session.steps.size(); ++s) {
    const SessionStep& step = session.steps[s];
    result.capture_seconds += step.seconds;
    std::vector<LaserScanPoints> clouds;
    bool used = false;
    if (stereo) {
      if (const auto frames = load_stereo_step(session, step, result.problems)) {
        clouds = {stereo_step_points(*frames, *stereo_setup)};
        used = true;
      }
    } else if (const auto frames = load_step(session, step, lasers, result.problems)) {
      clouds = step_points(*frames, geometry, result.parameters);
      used = true;
    }
    if (used) {
      for (std::size_t l = 0; l < clouds.size(); ++l) {
        append_points(result.by_laser[l], clouds[l]);
        result.points_thinned += spacing.thin(clouds[l]);
        append_points(result.points, clouds[l]);
      }
      ++result.steps_used;
    }
    if (options.on_step) options.on_step(step.step, step.angle_deg, clouds, result.points.cloud.size());
    if (options.progress) options.progress(double(s + 1) / double(session.steps.size()));
  }
  if (result.by_laser.size() == 2)
    result.laser_agreement = check_laser_agreement(result.by_laser[0].cloud.positions,
                                                   result.by_laser[1].cloud.positions, manifest.steps);
  const double outlier_radius = stereo ? result.stereo_parameters.outlier_radius : result.parameters.outlier_radius;
  const int outlier_neighbours =
      stereo ? result.stereo_parameters.outlier_neighbours : result.parameters.outlier_neighbours;
  if (outlier_radius > 0) {
    result.outliers_removed =
        remove_isolated_points(result.points, outlier_radius, outlier_neighbours, &result.fed_index);
    if (result.outliers_removed == 0) result.fed_index.clear();
  }
  result.points.cloud.positions = own_coordinates(result.points.cloud.positions, manifest.object.placement);
  result.process_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

std::optional<std::string> laser_agreement_warning(const ScanResult& result) {
  if (!result.laser_agreement) return std::nullopt;
  std::string message = laser_disagreement_message(*result.laser_agreement);
  if (message.empty()) return std::nullopt;
  return message;
}

json write_scan_results(const fs::path& folder, const SessionContents& session, const ScanResult& result,
                        const json& extra, io::Overwrite overwrite) {
  io::make_folder(folder);
  io::write_points(folder / "points.ply", result.points.cloud, {std::nullopt, std::nullopt, overwrite});
  json per_laser = json::array();
  for (const LaserScanPoints& laser : result.by_laser) per_laser.push_back(laser.cloud.size());
  const SessionManifest& m = session.manifest;
  json report = {
      {"scanstation", {{"version", kVersion}}},
      {"session", session.folder.string()},
      {"rig", m.rig},
      {"object", {{"name", m.object.name}, {"mesh_file", m.object.mesh_file}}},
      {"geometry_source", result.geometry.source},
      {"geometry",
       {{"source", result.geometry.source},
        {"recorded", result.recorded_geometry},
        {"calibration", result.geometry.calibration}}},
      {"steps", {{"planned", m.steps}, {"recorded", session.steps.size()}, {"used", result.steps_used}}},
      {"complete", static_cast<int>(session.steps.size()) == m.steps && result.steps_used == m.steps},
      {"points", result.points.cloud.size()},
      {"points_per_laser", per_laser},
      {"points_thinned", result.points_thinned},
      {"outliers_removed", result.outliers_removed},
      {"parameters", m.rig == "stereo" ? to_json(result.stereo_parameters) : to_json(result.parameters)},
      {"problems", result.problems},
      {"laser_agreement", result.laser_agreement ? to_json(*result.laser_agreement) : json(nullptr)},
      {"seconds", {{"capture", result.capture_seconds}, {"processing", result.process_seconds}}},
      {"replay_speedup", result.process_seconds > 0 ? json(result.capture_seconds / result.process_seconds)
                                                    : json(nullptr)},
      {"outputs", {{"points", (folder / "points.ply").string()}}}};
  if (extra.is_object()) report.update(extra);
  io::write_file_atomically(folder / "report.json", report.dump(2) + "\n", overwrite);
  return report;
}

}  // namespace scanstation::acquisition
