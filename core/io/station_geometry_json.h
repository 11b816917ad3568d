// JSON form of the station geometry (core/station_geometry.h), shared by the
// calibration file and the session manifest so both read and write the same,
// human-readable keys:
//
//   camera: {"width", "height", "fx", "fy", "cx", "cy",
//            "distortion": {"k1","k2","p1","p2","k3"},
//            "rotation": [[r00,r01,r02],[r10,r11,r12],[r20,r21,r22]],  // station → camera
//            "translation": [tx,ty,tz]}
//   laser:  {"origin": [x,y,z], "normal": [nx,ny,nz]}                  // station frame
#pragma once

#include "core/station_geometry.h"

#include <nlohmann/json.hpp>
#include <string>

namespace scanstation {

nlohmann::json to_json(const PinholeCamera& camera);
nlohmann::json to_json(const LaserPlane& plane);

/// Read back what to_json wrote. `where` names the document and key for error
/// messages (e.g. "calibration.json: camera"); a missing key, a wrong type, a
/// non-finite number, a non-positive size or focal length, a rotation that is
/// not orthonormal or a zero normal throws InvalidInput naming the field.
PinholeCamera pinhole_camera_from_json(const nlohmann::json& value, const std::string& where);
LaserPlane laser_plane_from_json(const nlohmann::json& value, const std::string& where);

}  // namespace scanstation
