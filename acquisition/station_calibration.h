// The calibration file of a station: one human-readable JSON document holding
// the camera (intrinsics, distortion, pose in the station frame), the
// turntable axis, the laser planes and the stereo pair when there is one,
// each with its residuals and date, plus the software version and a
// fingerprint of the station description (devices and image size), so that a
// scan refuses a calibration made for other devices.
//
//   {"format": "scanstation-calibration", "format_version": 1,
//    "software_version": "0.1.0", "created": "2026-12-01T17:00:00Z", "updated": "...",
//    "station": {"name": "sim", "fingerprint": "fnv1a64:…", "devices": {camera, lasers, turntable, usb}},
//    "camera":    {"date", "views", "geometry": <camera, core/io/station_geometry_json.h>,
//                  "pose": "station" | "camera", "residuals": {"rms_px", "per_view_rms_px"}},
//    "turntable": {"date", "views", "axis_camera": [x,y,z], "origin_camera": [x,y,z],
//                  "angles_deg": [...], "measured_angles_deg": [...],
//                  "residuals": {"rms", "max", "angle_rms_deg"}},
//    "lasers":    [{"index", "date", "views", "plane": <laser plane, station frame>,
//                   "residuals": {"rms", "max", "inliers", "points"}}],
//    "stereo":    {"date", "pairs", "left": <camera>, "right": <camera, pose relative to left>,
//                  "pose": "station" | "camera" (left camera placed on the turntable or not),
//                  "residuals": {"rms_px", "per_view_rms_px": [[left, right], ...]},
//                  "turntable": <as "turntable", in the left camera's frame> (when posed)}}
//
// Lengths are in the unit of the board's square size (millimetres by convention).
#pragma once

#include "core/io/file_access.h"
#include "core/station_geometry.h"
#include "drivers/station_description.h"

#include <nlohmann/json.hpp>

#include <array>

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace scanstation::acquisition {

/// The devices and image size a calibration is valid for: the parts of a
/// station description that change the geometry (not timeouts or exposure).
/// `hash` is FNV-1a 64 of the canonical JSON of `devices`.
struct StationFingerprint {
  std::string name;
  nlohmann::json devices;
  std::string hash;
};

StationFingerprint station_fingerprint(const drivers::StationDescription& station);

/// camera     intrinsics and distortion; pose in the station frame once the
///            turntable is calibrated (posed), the identity before
struct CameraPart {
  std::string date;
  std::size_t views = 0;
  PinholeCamera camera;
  bool posed = false;
  double rms = 0;  // px
  std::vector<double> per_view_rms;
};

/// Axis and platter origin in the camera frame, as calibrated (the camera's
/// station pose is derived from them); lengths in station units.
struct TurntablePart {
  std::string date;
  Eigen::Vector3d axis_camera = Eigen::Vector3d::UnitZ(), origin_camera = Eigen::Vector3d::Zero();
  std::vector<double> angles, measured_angles;  // radians (degrees in the file)
  double rms = 0, max = 0, angle_rms = 0;
};

struct LaserPart {
  int index = 0;
  std::string date;
  std::size_t views = 0;
  LaserPlane plane;  // station frame
  double rms = 0, max = 0;
  std::size_t inliers = 0, points = 0;
};

/// left   at the identity pose, or in the station frame once the turntable
///        axis was calibrated through it (posed, turntable set)
/// right  relative to left: x_right = rotation · x_left + translation
/// turntable  axis and platter origin in the left camera's frame
struct StereoPart {
  std::string date;
  std::size_t pairs = 0;
  PinholeCamera left, right;
  double rms = 0;
  std::vector<std::array<double, 2>> per_view_rms;
  std::optional<TurntablePart> turntable;
};


struct StationCalibration {
  std::filesystem::path source;  // the file read ("" when built in memory)
  std::string software_version, created, updated;
  StationFingerprint station;
  std::optional<CameraPart> camera;
  std::optional<TurntablePart> turntable;
  std::vector<LaserPart> lasers;  // by index, at most one per laser
  std::optional<StereoPart> stereo;

  /// The laser part of laser `index`, or nullptr.
  const LaserPart* laser(int index) const;
};

nlohmann::json to_json(const StationCalibration& calibration);
/// Throws InvalidInput naming `file` and the field for anything missing or malformed.
StationCalibration station_calibration_from_json(const nlohmann::json& document, const std::filesystem::path& file);

/// Reads a calibration file; errors name the file and field (FormatError for
/// text that is not JSON, with its line).
StationCalibration read_station_calibration(const std::filesystem::path& file);
/// Writes atomically (core/io/file_access.h), pretty-printed.
void write_station_calibration(const std::filesystem::path& file, const StationCalibration& calibration,
                               io::Overwrite overwrite);

/// Throws InvalidInput when the calibration was made for other devices than
/// `station` has: names the calibration file and every field that differs
/// (e.g. "camera.width: calibrated 640, station 1280").
void check_calibration_matches(const StationCalibration& calibration, const drivers::StationDescription& station);
/// The same against a fingerprint (e.g. the one a session recorded).
void check_calibration_matches(const StationCalibration& calibration, const StationFingerprint& station);

/// What a scan needs of a calibration.
enum class CalibrationNeed { camera_pose, lasers, stereo, stereo_pose };
/// Throws InvalidInput naming the file, what is missing and the command that
/// provides it: the camera and its station pose (calibrate camera, then
/// turntable), a plane for each of the station's `laser_count` lasers, the
/// stereo pair, the stereo pair placed on the turntable.
void check_calibration_complete(const StationCalibration& calibration, CalibrationNeed need, int laser_count = 0);

/// Stores a fresh camera calibration. A new camera invalidates the turntable
/// and laser parts (their poses were measured through the old intrinsics):
/// they are dropped; returns the names of the parts dropped.
std::vector<std::string> set_camera(StationCalibration& calibration, CameraPart camera);
/// Stores a turntable calibration and places the camera in the station frame;
/// laser planes already calibrated keep their place relative to the camera
/// (they are re-expressed in the new station frame). Requires the camera part.
void set_turntable(StationCalibration& calibration, TurntablePart turntable);
/// Stores (or replaces) the plane of laser part.index.
void set_laser(StationCalibration& calibration, LaserPart laser);
/// Stores a fresh stereo calibration: `turntable` (the axis seen by its left
/// camera), when given, places the pair in the station frame — the axis is
/// z, the platter top the origin, and y points from the middle between the
/// two cameras towards the axis (the simulator's convention, so that points
/// compare with its truth without a turn about the axis).
void set_stereo(StationCalibration& calibration, StereoPart stereo, std::optional<TurntablePart> turntable);

/// Both cameras of a posed stereo part in the station frame: the left as
/// stored, the right composed with it.
std::pair<PinholeCamera, PinholeCamera> stereo_cameras(const StereoPart& stereo);

/// UTC time as ISO 8601 ("2026-12-01T17:00:00Z"), from SOURCE_DATE_EPOCH
/// when set (reproducible files), else the system clock.
std::string calibration_date();

}  // namespace scanstation::acquisition
