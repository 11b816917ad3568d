#include "core/io/station_geometry_json.h"

#include "core/errors.h"

#include <cmath>

namespace scanstation {
namespace {

using nlohmann::json;

const json& field(const json& object, const char* key, const std::string& where) {
  if (!object.is_object()) throw InvalidInput(where + ": expected an object");
  const auto it = object.find(key);
  if (it == object.end()) throw InvalidInput(where + ": missing key \"" + key + "\"");
  return *it;
}

double number(const json& object, const char* key, const std::string& where) {
  const json& value = field(object, key, where);
  if (!value.is_number() || !std::isfinite(value.get<double>()))
    throw InvalidInput(where + "." + key + ": expected a finite number");
  return value.get<double>();
}

int positive_integer(const json& object, const char* key, const std::string& where) {
  const json& value = field(object, key, where);
  if (!value.is_number_integer() || value.get<long long>() <= 0 || value.get<long long>() > 1 << 20)
    throw InvalidInput(where + "." + key + ": expected a positive integer");
  return value.get<int>();
}

Eigen::Vector3d vector3(const json& value, const std::string& name) {
  if (!value.is_array() || value.size() != 3) throw InvalidInput(name + ": expected an array of 3 numbers");
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i) {
    if (!value[i].is_number() || !std::isfinite(value[i].get<double>()))
      throw InvalidInput(name + ": expected an array of 3 finite numbers");
    v[i] = value[i].get<double>();
  }
  return v;
}

Eigen::Vector3d vector3(const json& object, const char* key, const std::string& where) {
  return vector3(field(object, key, where), where + "." + key);
}

json array(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }

}  // namespace

json to_json(const PinholeCamera& camera) {
  const BrownConrady& d = camera.distortion;
  json rotation = json::array();
  for (int r = 0; r < 3; ++r) rotation.push_back(array(camera.rotation.row(r).transpose()));
  return {{"width", camera.width},
          {"height", camera.height},
          {"fx", camera.fx},
          {"fy", camera.fy},
          {"cx", camera.cx},
          {"cy", camera.cy},
          {"distortion", {{"k1", d.k1}, {"k2", d.k2}, {"p1", d.p1}, {"p2", d.p2}, {"k3", d.k3}}},
          {"rotation", rotation},
          {"translation", array(camera.translation)}};
}

json to_json(const LaserPlane& plane) { return {{"origin", array(plane.origin)}, {"normal", array(plane.normal)}}; }

PinholeCamera pinhole_camera_from_json(const json& value, const std::string& where) {
  PinholeCamera camera;
  camera.width = positive_integer(value, "width", where);
  camera.height = positive_integer(value, "height", where);
  camera.fx = number(value, "fx", where);
  camera.fy = number(value, "fy", where);
  if (!(camera.fx > 0) || !(camera.fy > 0)) throw InvalidInput(where + ": expected positive focal lengths fx, fy");
  camera.cx = number(value, "cx", where);
  camera.cy = number(value, "cy", where);
  const json& d = field(value, "distortion", where);
  const std::string dw = where + ".distortion";
  camera.distortion = {number(d, "k1", dw), number(d, "k2", dw), number(d, "k3", dw), number(d, "p1", dw),
                       number(d, "p2", dw)};
  const json& rotation = field(value, "rotation", where);
  if (!rotation.is_array() || rotation.size() != 3)
    throw InvalidInput(where + ".rotation: expected 3 rows of 3 numbers");
  for (int r = 0; r < 3; ++r)
    camera.rotation.row(r) = vector3(rotation[r], where + ".rotation[" + std::to_string(r) + "]").transpose();
  // A pose read back from a file is a rotation to printing precision; anything
  // farther off is a damaged or hand-edited file, not a rounding.
  if ((camera.rotation * camera.rotation.transpose() - Eigen::Matrix3d::Identity()).norm() > 1e-6 ||
      camera.rotation.determinant() < 0)
    throw InvalidInput(where + ".rotation: expected a proper orthonormal matrix (station → camera)");
  camera.translation = vector3(value, "translation", where);
  return camera;
}

LaserPlane laser_plane_from_json(const json& value, const std::string& where) {
  LaserPlane plane;
  plane.origin = vector3(value, "origin", where);
  const Eigen::Vector3d normal = vector3(value, "normal", where);
  if (!(normal.norm() > 1e-12)) throw InvalidInput(where + ".normal: expected a non-zero vector");
  plane.normal = normal.normalized();
  return plane;
}

}  // namespace scanstation
