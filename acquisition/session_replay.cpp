#include "acquisition/session_replay.h"

#include "acquisition/outlier_removal.h"
#include "core/errors.h"
#include "core/io/mesh_io.h"
#include "core/version.h"

#include <chrono>
#include <opencv2/imgcodecs.hpp>

namespace scanstation::acquisition {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// The frames of one step that can be used, with a problem noted for each
// that cannot. No laser-off frame → no frames at all.
std::optional<StepFrames> load_step(const SessionContents& session, const SessionStep& step,
                                    const std::vector<int>& lasers, std::vector<std::string>& problems) {
  StepFrames frames;
  frames.angle_deg = step.angle_deg;
  const auto unusable = [&](const SessionFrame& f, const char* what, const std::string& consequence) {
    problems.push_back((session.folder / f.file).string() + ": " + what + " (journal line " +
                       std::to_string(step.journal_line) + "): " + consequence);
  };
  const auto load = [&](const SessionFrame& f) {
    const fs::path path = session.folder / f.file;
    return fs::exists(path) ? read_session_frame(path) : cv::Mat();
  };
  const auto off = std::find_if(step.frames.begin(), step.frames.end(), [](const SessionFrame& f) { return !f.laser; });
  const std::string step_name = "step " + std::to_string(step.step);
  if (off == step.frames.end()) {
    problems.push_back("journal line " + std::to_string(step.journal_line) + ": " + step_name +
                       " has no laser-off frame: step skipped");
    return std::nullopt;
  }
  frames.off = load(*off);
  if (frames.off.empty()) {
    unusable(*off, fs::exists(session.folder / off->file) ? "unreadable" : "missing", step_name + " skipped");
    return std::nullopt;
  }
  for (const SessionFrame& f : step.frames) {
    if (!f.laser || std::find(lasers.begin(), lasers.end(), *f.laser) == lasers.end()) continue;
    cv::Mat on = load(f);
    if (on.empty()) {
      unusable(f, fs::exists(session.folder / f.file) ? "unreadable" : "missing",
               step_name + " laser " + std::to_string(*f.laser) + " skipped");
      continue;
    }
    frames.on.emplace_back(*f.laser, std::move(on));
  }
  return frames;
}

}  // namespace

cv::Mat read_session_frame(const fs::path& file) { return cv::imread(file.string(), cv::IMREAD_UNCHANGED); }

ScanResult replay_session(const SessionContents& session, const ReplayOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  ScanResult result;
  result.problems = session.problems;
  result.parameters = options.parameters.value_or(session.manifest.parameters);
  result.geometry = options.geometry.value_or(session.manifest.geometry);
  result.recorded_geometry = !options.geometry;
  const TurntableGeometry& geometry = result.geometry;
  std::vector<int> lasers = session.lasers;
  if (options.geometry) {
    lasers.clear();
    for (std::size_t i = 0; i < geometry.lasers.size(); ++i) lasers.push_back(static_cast<int>(i));
  }
  result.by_laser.resize(geometry.lasers.size());
  for (std::size_t s = 0; s < session.steps.size(); ++s) {
    const SessionStep& step = session.steps[s];
    result.capture_seconds += step.seconds;
    std::vector<LaserScanPoints> clouds;
    if (const auto frames = load_step(session, step, lasers, result.problems)) {
      clouds = step_points(*frames, geometry, result.parameters);
      for (std::size_t l = 0; l < clouds.size(); ++l) {
        append_points(result.points, clouds[l]);
        append_points(result.by_laser[l], clouds[l]);
      }
      ++result.steps_used;
    }
    if (options.on_step) options.on_step(step.step, step.angle_deg, clouds, result.points.cloud.size());
    if (options.progress) options.progress(double(s + 1) / double(session.steps.size()));
  }
  if (result.by_laser.size() == 2)
    result.laser_agreement = check_laser_agreement(result.by_laser[0].cloud.positions,
                                                   result.by_laser[1].cloud.positions, session.manifest.steps);
  if (result.parameters.outlier_radius > 0)
    result.outliers_removed =
        remove_isolated_points(result.points, result.parameters.outlier_radius, result.parameters.outlier_neighbours);
  result.points.cloud.positions = own_coordinates(result.points.cloud.positions, session.manifest.object.placement);
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
  fs::create_directories(folder);
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
      {"outliers_removed", result.outliers_removed},
      {"parameters", to_json(result.parameters)},
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
