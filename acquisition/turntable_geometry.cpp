#include "acquisition/turntable_geometry.h"

#include "core/io/station_geometry_json.h"

#include <cstdio>

namespace scanstation::acquisition {

TurntableGeometry simulator_truth(const PinholeCamera& camera, std::vector<LaserPlane> planes) {
  TurntableGeometry geometry;
  geometry.camera = camera;
  geometry.lasers = std::move(planes);
  geometry.source = "simulator truth";
  return geometry;
}

nlohmann::json to_json(const TurntableGeometry& geometry) {
  nlohmann::json lasers = nlohmann::json::array();
  for (const LaserPlane& plane : geometry.lasers) lasers.push_back(scanstation::to_json(plane));
  nlohmann::json document = {
      {"source", geometry.source}, {"camera", scanstation::to_json(geometry.camera)}, {"lasers", lasers}};
  if (!geometry.calibration.is_null()) document["calibration"] = geometry.calibration;
  return document;
}

std::string json_digest(const nlohmann::json& value) {
  std::uint64_t hash = 0xCBF29CE484222325ull;
  for (const unsigned char c : value.dump()) {
    hash ^= c;
    hash *= 0x100000001B3ull;
  }
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash));
  return text;
}

}  // namespace scanstation::acquisition
