#include "acquisition/scan_calibration.h"

#include "core/errors.h"

#include <cmath>
#include <cstdio>
#include <ctime>
#include <tuple>

namespace scanstation::acquisition {

using nlohmann::json;

long long seconds_since_epoch(const std::string& iso_time, const std::string& field) {
  std::tm utc{};
  char zone = 0;
  int consumed = 0;
  if (std::sscanf(iso_time.c_str(), "%4d-%2d-%2dT%2d:%2d:%2d%c%n", &utc.tm_year, &utc.tm_mon, &utc.tm_mday,
                  &utc.tm_hour, &utc.tm_min, &utc.tm_sec, &zone, &consumed) != 7 ||
      zone != 'Z' || static_cast<std::size_t>(consumed) != iso_time.size())
    throw InvalidInput(field + ": \"" + iso_time + "\" is not a UTC time like 2026-12-01T17:00:00Z");
  utc.tm_year -= 1900;
  utc.tm_mon -= 1;
  return static_cast<long long>(timegm(&utc));
}

TurntableGeometry calibrated_geometry(const StationCalibration& calibration, const StationFingerprint& station,
                                      int laser_count, double max_age_days, const std::string& now,
                                      CalibrationNeed need) {
  const bool stereo = need == CalibrationNeed::stereo || need == CalibrationNeed::stereo_pose;
  check_calibration_matches(calibration, station);
  check_calibration_complete(calibration, stereo ? CalibrationNeed::stereo_pose : CalibrationNeed::lasers, laser_count);
  const std::string file = calibration.source.empty() ? "the calibration" : calibration.source.string();

  // The parts used, with their dates: the oldest decides the age.
  std::vector<std::pair<std::string, std::string>> parts;
  json laser_dates = json::array();
  if (stereo) {
    parts = {{"stereo.date", calibration.stereo->date}, {"stereo.turntable.date", calibration.stereo->turntable->date}};
  } else {
    parts.emplace_back("camera.date", calibration.camera->date);
    if (calibration.turntable) parts.emplace_back("turntable.date", calibration.turntable->date);
    for (int l = 0; l < laser_count; ++l) {
      parts.emplace_back("lasers[" + std::to_string(l) + "].date", calibration.laser(l)->date);
      laser_dates.push_back(calibration.laser(l)->date);
    }
  }
  // The cameras' image size against the devices': the fingerprint covers the
  // station's side only, and an edited camera part stopped the scan after its
  // first step.
  const json& device = station.devices.value("camera", json::object());
  const auto check_size = [&](const PinholeCamera& camera, const char* field) {
    if (device.contains("width") && device.contains("height") &&
        (camera.width != device["width"].get<int>() || camera.height != device["height"].get<int>()))
      throw InvalidInput(file + ": " + field + " is " + std::to_string(camera.width) + "x" +
                         std::to_string(camera.height) + ", the station's camera delivers " +
                         device["width"].dump() + "x" + device["height"].dump() + ": recalibrate it");
  };
  if (stereo) {
    check_size(calibration.stereo->left, "stereo.left");
  } else {
    check_size(calibration.camera->camera, "camera");
  }
  const long long at = seconds_since_epoch(now, "the current time");
  double age_days = 0;
  std::string oldest;
  for (const auto& [field, date] : parts) {
    const double age = static_cast<double>(at - seconds_since_epoch(date, file + ": " + field)) / 86400.0;
    // A day of clock skew between machines is allowed; more is an edited
    // file or a wrong clock, and the age check would never fire.
    if (age < -1.0)
      throw InvalidInput(file + ": " + field + " " + date + " lies " + std::to_string(static_cast<long long>(-age)) +
                         " days in the future: check this machine's clock, or recalibrate that part");
    if (age >= age_days) {
      age_days = age;
      oldest = field;
    }
  }
  if (max_age_days > 0 && age_days > max_age_days) {
    char text[160];
    std::snprintf(text, sizeof text, " is stale: its %s is %.1f days old, more than the %.0f days accepted", oldest.c_str(),
                  age_days, max_age_days);
    const std::string part = oldest.substr(0, oldest.find_first_of(".["));  // "lasers[1].date": calibrate laser
    throw InvalidInput(file + text + ": recalibrate that part (`scanstation calibrate " +
                       (part == "lasers" ? "laser" : part) + " --force`" +
                       (stereo ? "" : ", with `calibrate laser` after a new camera or turntable") +
                       "), or accept it with --calibration-max-age DAYS (0: any age)");
  }

  TurntableGeometry geometry;
  json dates;
  if (stereo) {
    std::tie(geometry.camera, geometry.right_camera) = stereo_cameras(*calibration.stereo);
    dates = {{"stereo", calibration.stereo->date}, {"turntable", calibration.stereo->turntable->date}};
  } else {
    geometry.camera = calibration.camera->camera;
    for (int l = 0; l < laser_count; ++l) geometry.lasers.push_back(calibration.laser(l)->plane);
    dates = {{"camera", calibration.camera->date},
             {"turntable", calibration.turntable ? json(calibration.turntable->date) : json(nullptr)},
             {"lasers", laser_dates}};
  }
  geometry.source = file;
  geometry.calibration = {{"file", file},
                          {"fingerprint", calibration.station.hash},
                          {"created", calibration.created},
                          {"updated", calibration.updated},
                          {"dates", dates},
                          {"age_days", std::round(age_days * 1000) / 1000}};
  return geometry;
}

TurntableGeometry scan_geometry(const std::string& choice, const drivers::StationDescription& station,
                                const std::optional<TurntableGeometry>& simulator_truth, double max_age_days,
                                CalibrationNeed need) {
  const bool stereo = need == CalibrationNeed::stereo || need == CalibrationNeed::stereo_pose;
  const std::string file = choice.empty() ? station.calibration.string() : choice;
  if (file == kSimulatorTruth || (file.empty() && simulator_truth)) {
    if (!simulator_truth)
      throw InvalidInput(std::string("--calibration ") + kSimulatorTruth +
                         ": only a simulated station has a true geometry; give the station's calibration file");
    return *simulator_truth;
  }
  if (file.empty())
    throw InvalidInput("scan: the station's devices are real and no calibration is given: name the calibration file "
                       "with --calibration FILE or `calibration = \"FILE\"` in the station description (make one "
                       "with " + std::string(stereo ? "`scanstation calibrate stereo`" :
                                             "`scanstation calibrate camera`, then `turntable`, then `laser`") + ")");
  if (!std::filesystem::exists(file))
    throw InvalidInput("calibration file " + file + " does not exist" +
                       (choice.empty() ? " (named by the station description " + station.source.string() + ")" : "") +
                       ": make it with `scanstation calibrate " + (stereo ? "stereo" : "camera|turntable|laser") +
                       " -o " + file + "`");
  return calibrated_geometry(read_station_calibration(file), station_fingerprint(station),
                             static_cast<int>(station.lasers.size()), max_age_days, calibration_date(), need);
}

TurntableGeometry replay_geometry(const std::filesystem::path& file, const SessionContents& session,
                                  double max_age_days) {
  const std::string replay = "replay of " + session.folder.string() + ": ";
  const json& station = session.manifest.station;
  const json* recorded = station.contains("fingerprint") ? &station["fingerprint"] : nullptr;
  if (!recorded || !recorded->contains("hash") || !recorded->contains("devices") ||
      !(*recorded)["devices"].value("lasers", json()).is_array())
    throw InvalidInput(replay + "its manifest records no station.fingerprint (an older session): the devices it was "
                       "scanned with are unknown, so " + file.string() + " cannot be checked against them; replay "
                       "it with its recorded geometry");
  if (!std::filesystem::exists(file)) throw InvalidInput(replay + "calibration file " + file.string() + " does not exist");
  StationFingerprint fingerprint;
  fingerprint.name = station.value("name", std::string());
  fingerprint.hash = (*recorded)["hash"].get<std::string>();
  fingerprint.devices = (*recorded)["devices"];
  try {
    return calibrated_geometry(read_station_calibration(file), fingerprint,
                               static_cast<int>(fingerprint.devices["lasers"].size()), max_age_days, calibration_date(),
                               session.manifest.rig == "stereo" ? CalibrationNeed::stereo_pose : CalibrationNeed::lasers);
  } catch (const InvalidInput& e) {
    throw InvalidInput(replay + e.what());
  }
}

}  // namespace scanstation::acquisition
