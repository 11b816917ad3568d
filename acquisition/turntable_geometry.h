// The geometry a turntable laser scan is triangulated with: the camera and
// the light planes, in the station frame (core/station_geometry.h). One
// parameter object, so the simulator's truth, a calibration file or a
// session's recorded geometry plug in alike.
#pragma once

#include "core/station_geometry.h"

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace scanstation::acquisition {

/// camera  the calibrated camera (intrinsics, distortion, pose)
/// lasers  light plane of laser i at index i
/// source  where it came from ("simulator truth", a calibration file, ...)
/// calibration  what identifies the calibration file it came from (its
///         station fingerprint, dates; scan_calibration.h), null otherwise
struct TurntableGeometry {
  PinholeCamera camera;
  std::vector<LaserPlane> lasers;
  std::string source;
  nlohmann::json calibration;
};

/// A geometry known exactly, the simulator's truth: `camera` and the light
/// `planes` (laser i at index i), source "simulator truth", no calibration.
TurntableGeometry simulator_truth(const PinholeCamera& camera, std::vector<LaserPlane> planes);

/// {"source", "camera": {...}, "lasers": [{...}, ...], "calibration": {...}}
/// with the keys of core/io/station_geometry_json.h ("calibration" only when
/// not null).
nlohmann::json to_json(const TurntableGeometry& geometry);

/// A digest (FNV-1a, 16 hex digits) of a JSON value's compact text: recorded
/// next to the geometry so that a later edit is noticed. Not a security
/// measure, a check against accidents.
std::string json_digest(const nlohmann::json& value);

}  // namespace scanstation::acquisition
