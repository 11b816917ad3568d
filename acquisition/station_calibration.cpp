#include "acquisition/station_calibration.h"

#include "acquisition/laser_plane_calibration.h"
#include "acquisition/stereo_reconstruction.h"
#include "acquisition/turntable_axis_calibration.h"
#include "core/errors.h"
#include "core/io/json_document.h"
#include "core/io/station_geometry_json.h"
#include "core/version.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <numbers>

namespace scanstation::acquisition {

using nlohmann::json;

namespace {

constexpr const char* kFormat = "scanstation-calibration";
constexpr int kFormatVersion = 1;
constexpr double degree = std::numbers::pi / 180.0;

std::string fnv1a64(const std::string& text) {
  std::uint64_t hash = 0xcbf29ce484222325ull;
  for (const unsigned char c : text) hash = (hash ^ c) * 0x100000001b3ull;
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(hash));
  return std::string("fnv1a64:") + hex;
}

json array(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }

json scaled(const std::vector<double>& values, double factor) {
  json out = json::array();
  for (const double v : values) out.push_back(v * factor);
  return out;
}

// Field readers naming "file: path.key" in every error.
class Fields {
 public:
  Fields(const json& object, std::string where) : object_(object), where_(std::move(where)) {
    if (!object_.is_object()) throw InvalidInput(where_ + ": expected an object");
  }
  std::string name(const std::string& key) const { return where_ + "." + key; }
  const json& at(const char* key) const {
    const auto it = object_.find(key);
    if (it == object_.end()) throw InvalidInput(where_ + ": missing key \"" + key + "\"");
    return *it;
  }
  bool has(const char* key) const { return object_.contains(key); }
  std::string text(const char* key) const {
    const json& v = at(key);
    if (!v.is_string()) throw InvalidInput(name(key) + ": expected a string");
    return v.get<std::string>();
  }
  double number(const char* key) const {
    const json& v = at(key);
    if (!v.is_number() || !std::isfinite(v.get<double>())) throw InvalidInput(name(key) + ": expected a finite number");
    return v.get<double>();
  }
  std::size_t count(const char* key) const {
    const json& v = at(key);
    if (!v.is_number_unsigned()) throw InvalidInput(name(key) + ": expected a count (an integer ≥ 0)");
    return v.get<std::size_t>();
  }
  std::vector<double> numbers(const char* key, double factor = 1.0) const {
    const json& v = at(key);
    if (!v.is_array()) throw InvalidInput(name(key) + ": expected an array of numbers");
    std::vector<double> out;
    for (const json& x : v) {
      if (!x.is_number() || !std::isfinite(x.get<double>())) throw InvalidInput(name(key) + ": expected finite numbers");
      out.push_back(x.get<double>() * factor);
    }
    return out;
  }
  Eigen::Vector3d vector3(const char* key) const {
    const std::vector<double> v = numbers(key);
    if (v.size() != 3) throw InvalidInput(name(key) + ": expected an array of 3 numbers");
    return {v[0], v[1], v[2]};
  }
  Fields object(const char* key) const { return Fields(at(key), name(key)); }

 private:
  const json& object_;
  std::string where_;
};

json camera_json(const CameraPart& part) {
  return {{"date", part.date}, {"views", part.views}, {"geometry", to_json(part.camera)},
          {"pose", part.posed ? "station" : "camera"},
          {"residuals", {{"rms_px", part.rms}, {"per_view_rms_px", part.per_view_rms}}}};
}

CameraPart camera_part(const Fields& f) {
  CameraPart part;
  part.date = f.text("date");
  part.views = f.count("views");
  part.camera = pinhole_camera_from_json(f.at("geometry"), f.name("geometry"));
  const std::string pose = f.text("pose");
  if (pose != "station" && pose != "camera") throw InvalidInput(f.name("pose") + ": expected \"station\" or \"camera\"");
  part.posed = pose == "station";
  const Fields residuals = f.object("residuals");
  part.rms = residuals.number("rms_px");
  part.per_view_rms = residuals.numbers("per_view_rms_px");
  return part;
}

json turntable_json(const TurntablePart& part) {
  return {{"date", part.date},
          {"views", part.angles.size()},
          {"axis_camera", array(part.axis_camera)},
          {"origin_camera", array(part.origin_camera)},
          {"angles_deg", scaled(part.angles, 1 / degree)},
          {"measured_angles_deg", scaled(part.measured_angles, 1 / degree)},
          {"residuals", {{"rms", part.rms}, {"max", part.max}, {"angle_rms_deg", part.angle_rms / degree}}}};
}

TurntablePart turntable_part(const Fields& f) {
  TurntablePart part;
  part.date = f.text("date");
  part.axis_camera = f.vector3("axis_camera");
  if (!(std::abs(part.axis_camera.norm() - 1.0) < 1e-6)) throw InvalidInput(f.name("axis_camera") + ": expected a unit vector");
  part.origin_camera = f.vector3("origin_camera");
  part.angles = f.numbers("angles_deg", degree);
  part.measured_angles = f.numbers("measured_angles_deg", degree);
  const Fields residuals = f.object("residuals");
  part.rms = residuals.number("rms");
  part.max = residuals.number("max");
  part.angle_rms = residuals.number("angle_rms_deg") * degree;
  return part;
}

json laser_json(const LaserPart& part) {
  return {{"index", part.index}, {"date", part.date}, {"views", part.views}, {"plane", to_json(part.plane)},
          {"residuals", {{"rms", part.rms}, {"max", part.max}, {"inliers", part.inliers}, {"points", part.points}}}};
}

LaserPart laser_part(const Fields& f) {
  LaserPart part;
  const std::size_t index = f.count("index");
  if (index > 63) throw InvalidInput(f.name("index") + ": expected a laser index below 64");
  part.index = static_cast<int>(index);
  part.date = f.text("date");
  part.views = f.count("views");
  part.plane = laser_plane_from_json(f.at("plane"), f.name("plane"));
  const Fields residuals = f.object("residuals");
  part.rms = residuals.number("rms");
  part.max = residuals.number("max");
  part.inliers = residuals.count("inliers");
  part.points = residuals.count("points");
  return part;
}

json matrix_rows(const cv::Mat& m) {
  json rows = json::array();
  for (int r = 0; r < m.rows; ++r) {
    json row = json::array();
    for (int c = 0; c < m.cols; ++c) row.push_back(m.at<double>(r, c));
    rows.push_back(row);
  }
  return rows;
}

json stereo_json(const StereoPart& part) {
  json per_view = json::array();
  for (const auto& v : part.per_view_rms) per_view.push_back({v[0], v[1]});
  // The rectification the scan uses (cv::stereoRectify of the two cameras),
  // written out for other programs; reading ignores it and derives it again.
  const auto [left, right] = stereo_cameras(part);
  const StereoCalibration rectified = stereo_station(left, right).calibration;
  json out = {{"date", part.date}, {"pairs", part.pairs}, {"left", to_json(part.left)}, {"right", to_json(part.right)},
              {"pose", part.turntable ? "station" : "camera"},
              {"residuals", {{"rms_px", part.rms}, {"per_view_rms_px", per_view}}},
              {"rectification",
               {{"derived", "cv::stereoRectify of left and right, principal points kept, alpha 0: what the scan uses; "
                            "reading derives it again"},
                {"R1", matrix_rows(rectified.r1)},
                {"R2", matrix_rows(rectified.r2)},
                {"P1", matrix_rows(rectified.p1)},
                {"P2", matrix_rows(rectified.p2)},
                {"Q", matrix_rows(rectified.q)}}}};
  if (part.turntable) out["turntable"] = turntable_json(*part.turntable);
  return out;
}

StereoPart stereo_part(const Fields& f) {
  StereoPart part;
  part.date = f.text("date");
  part.pairs = f.count("pairs");
  part.left = pinhole_camera_from_json(f.at("left"), f.name("left"));
  part.right = pinhole_camera_from_json(f.at("right"), f.name("right"));
  const Fields residuals = f.object("residuals");
  part.rms = residuals.number("rms_px");
  const json& per_view = residuals.at("per_view_rms_px");
  if (!per_view.is_array()) throw InvalidInput(residuals.name("per_view_rms_px") + ": expected [[left, right], ...]");
  for (const json& pair : per_view) {
    if (!pair.is_array() || pair.size() != 2 || !pair[0].is_number() || !pair[1].is_number())
      throw InvalidInput(residuals.name("per_view_rms_px") + ": expected [[left, right], ...]");
    part.per_view_rms.push_back({pair[0].get<double>(), pair[1].get<double>()});
  }
  // Files written before the pair could be placed on the turntable have no "pose".
  const std::string pose = f.has("pose") ? f.text("pose") : "camera";
  if (pose != "station" && pose != "camera") throw InvalidInput(f.name("pose") + ": expected \"station\" or \"camera\"");
  if ((pose == "station") != f.has("turntable"))
    throw InvalidInput(f.name("pose") + ": \"station\" goes with a \"turntable\" part, \"camera\" without one");
  if (f.has("turntable")) part.turntable = turntable_part(f.object("turntable"));
  return part;
}

// Every leaf where two fingerprints differ, as "path: calibrated A, station B".
void differences(const json& calibrated, const json& station, const std::string& path, std::vector<std::string>& out) {
  if (calibrated.is_object() && station.is_object()) {
    for (const auto& [key, value] : calibrated.items())
      differences(value, station.contains(key) ? station.at(key) : json(), path.empty() ? key : path + "." + key, out);
    for (const auto& [key, value] : station.items())
      if (!calibrated.contains(key)) differences(json(), value, path.empty() ? key : path + "." + key, out);
  } else if (calibrated.is_array() && station.is_array() && calibrated.size() != station.size()) {
    out.push_back(path + ": calibrated " + std::to_string(calibrated.size()) + ", station " +
                  std::to_string(station.size()));
  } else if (calibrated.is_array() && station.is_array()) {
    for (std::size_t i = 0; i < calibrated.size(); ++i)
      differences(calibrated[i], station[i], path + "[" + std::to_string(i) + "]", out);
  } else if (calibrated != station) {
    out.push_back(path + ": calibrated " + (calibrated.is_null() ? "(none)" : calibrated.dump()) + ", station " +
                  (station.is_null() ? "(none)" : station.dump()));
  }
}

}  // namespace

StationFingerprint station_fingerprint(const drivers::StationDescription& station) {
  StationFingerprint fingerprint;
  fingerprint.name = station.name;
  json& devices = fingerprint.devices;
  const drivers::CameraRole& camera = station.camera;
  devices["camera"] = {{"backend", camera.backend}, {"device", camera.backend == "v4l2" ? camera.device : "simulated"},
                       {"format", drivers::pixel_format_name(camera.format.format)},
                       {"width", camera.format.size.width}, {"height", camera.format.size.height}};
  bool usb = station.turntable.backend == "usb";
  devices["lasers"] = json::array();
  for (const drivers::LaserRole& laser : station.lasers) {
    json role = {{"backend", laser.backend}};
    if (laser.backend == "gpio") role["line"] = laser.line.describe();
    if (laser.backend == "usb") role["output"] = laser.usb_index;
    usb = usb || laser.backend == "usb";
    devices["lasers"].push_back(role);
  }
  // A stereo rig's second camera; absent for a laser rig, whose fingerprint stays as it was.
  if (station.right_camera) {
    const drivers::CameraRole& right = *station.right_camera;
    devices["right_camera"] = {{"backend", right.backend},
                               {"device", right.backend == "v4l2" ? right.device : "simulated"},
                               {"format", drivers::pixel_format_name(right.format.format)},
                               {"width", right.format.size.width}, {"height", right.format.size.height}};
  }
  devices["turntable"] = {{"backend", station.turntable.backend},
                          {"steps_per_rev", station.turntable.stepper.steps_per_rev()}};
  if (usb) devices["usb"] = station.usb.describe();
  fingerprint.hash = fnv1a64(devices.dump());
  return fingerprint;
}

const LaserPart* StationCalibration::laser(int index) const {
  for (const LaserPart& part : lasers)
    if (part.index == index) return &part;
  return nullptr;
}

json to_json(const StationCalibration& c) {
  json document = {{"format", kFormat},
                   {"format_version", kFormatVersion},
                   {"software_version", c.software_version},
                   {"created", c.created},
                   {"updated", c.updated},
                   {"station", {{"name", c.station.name}, {"fingerprint", c.station.hash}, {"devices", c.station.devices}}}};
  if (c.camera) document["camera"] = camera_json(*c.camera);
  if (c.turntable) document["turntable"] = turntable_json(*c.turntable);
  if (!c.lasers.empty()) {
    document["lasers"] = json::array();
    for (const LaserPart& laser : c.lasers) document["lasers"].push_back(laser_json(laser));
  }
  if (c.stereo) document["stereo"] = stereo_json(*c.stereo);
  return document;
}

StationCalibration station_calibration_from_json(const json& document, const std::filesystem::path& file) {
  const Fields top(document, file.string() + ": calibration");
  if (!top.has("format") || !document.at("format").is_string() || document.at("format") != kFormat)
    throw InvalidInput(file.string() + ": not a scanstation calibration file (expected \"format\": \"" + kFormat + "\")");
  const double version = top.number("format_version");
  if (version != kFormatVersion)
    throw InvalidInput(top.name("format_version") + ": version " + document.at("format_version").dump() +
                       " is not supported (expected " + std::to_string(kFormatVersion) + ")");
  StationCalibration c;
  c.source = file;
  c.software_version = top.text("software_version");
  c.created = top.text("created");
  c.updated = top.text("updated");
  const Fields station = top.object("station");
  c.station.name = station.text("name");
  c.station.hash = station.text("fingerprint");
  c.station.devices = station.at("devices");
  if (!c.station.devices.is_object()) throw InvalidInput(station.name("devices") + ": expected an object");
  if (fnv1a64(c.station.devices.dump()) != c.station.hash)
    throw InvalidInput(station.name("fingerprint") + ": does not match station.devices (the file was edited by hand?)");
  if (top.has("camera")) c.camera = camera_part(top.object("camera"));
  if (top.has("turntable")) c.turntable = turntable_part(top.object("turntable"));
  if (top.has("lasers")) {
    const json& lasers = top.at("lasers");
    if (!lasers.is_array()) throw InvalidInput(top.name("lasers") + ": expected an array");
    for (std::size_t i = 0; i < lasers.size(); ++i) {
      LaserPart part = laser_part(Fields(lasers[i], top.name("lasers") + "[" + std::to_string(i) + "]"));
      if (c.laser(part.index))
        throw InvalidInput(top.name("lasers") + "[" + std::to_string(i) + "].index: laser " +
                           std::to_string(part.index) + " appears twice");
      c.lasers.push_back(part);
    }
  }
  if (top.has("stereo")) c.stereo = stereo_part(top.object("stereo"));
  if (c.turntable && !c.camera) throw InvalidInput(top.name("turntable") + ": present without a camera part");
  return c;
}

StationCalibration read_station_calibration(const std::filesystem::path& file) {
  return station_calibration_from_json(io::read_json_document(file), file);
}

void write_station_calibration(const std::filesystem::path& file, const StationCalibration& calibration,
                               io::Overwrite overwrite) {
  io::write_file_atomically(file, to_json(calibration).dump(2) + "\n", overwrite);
}

void check_calibration_matches(const StationCalibration& calibration, const drivers::StationDescription& station) {
  check_calibration_matches(calibration, station_fingerprint(station));
}

void check_calibration_matches(const StationCalibration& calibration, const StationFingerprint& now) {
  if (now.hash == calibration.station.hash) return;
  std::vector<std::string> diff;
  differences(calibration.station.devices, now.devices, "", diff);
  std::string list;
  for (const std::string& d : diff) list += (list.empty() ? "" : "; ") + d;
  const std::string file = calibration.source.empty() ? "the calibration" : calibration.source.string();
  throw InvalidInput(file + " was made for other devices than station \"" + now.name + "\" has (" + list +
                     "): recalibrate with `scanstation calibrate` for this station");
}

void check_calibration_complete(const StationCalibration& c, CalibrationNeed need, int laser_count) {
  const std::string file = c.source.empty() ? "the calibration" : c.source.string();
  if (need == CalibrationNeed::stereo || need == CalibrationNeed::stereo_pose) {
    if (!c.stereo) throw InvalidInput(file + " has no stereo calibration: run `scanstation calibrate stereo`");
    if (need == CalibrationNeed::stereo_pose && !c.stereo->turntable)
      throw InvalidInput(file + " does not place the stereo pair on the turntable: run `scanstation calibrate stereo "
                         "--force` with the board on the platter at several angles (--turntable IMAGES "
                         "--angles|--step --lowest-corner-height, or --backend sim)");
    return;
  }
  if (!c.camera) throw InvalidInput(file + " has no camera calibration: run `scanstation calibrate camera`");
  if (!c.camera->posed)
    throw InvalidInput(file + " does not place the camera in the station frame: run `scanstation calibrate turntable`");
  if (need == CalibrationNeed::lasers)
    for (int l = 0; l < laser_count; ++l)
      if (!c.laser(l))
        throw InvalidInput(file + " has no plane for laser " + std::to_string(l) + ": run `scanstation calibrate laser`");
}

std::vector<std::string> set_camera(StationCalibration& c, CameraPart camera) {
  std::vector<std::string> dropped;
  if (c.turntable) dropped.push_back("turntable");
  for (const LaserPart& laser : c.lasers) dropped.push_back("laser " + std::to_string(laser.index));
  c.turntable.reset();
  c.lasers.clear();
  camera.posed = false;
  camera.camera.rotation.setIdentity();
  camera.camera.translation.setZero();
  c.camera = std::move(camera);
  return dropped;
}

void set_turntable(StationCalibration& c, TurntablePart turntable) {
  if (!c.camera) throw InvalidInput("turntable calibration: calibrate the camera first (`scanstation calibrate camera`)");
  const PinholeCamera old = c.camera->camera;
  TurntableAxis axis;
  axis.direction = turntable.axis_camera;
  axis.origin = turntable.origin_camera;
  c.camera->camera = place_camera(old, axis);
  c.camera->posed = true;
  // A plane stays where it is relative to the camera; only the frame moves.
  for (LaserPart& laser : c.lasers) laser.plane = to_station_frame(to_camera_frame(laser.plane, old), c.camera->camera);
  c.turntable = std::move(turntable);
}

void set_laser(StationCalibration& c, LaserPart laser) {
  for (LaserPart& part : c.lasers)
    if (part.index == laser.index) {
      part = std::move(laser);
      return;
    }
  c.lasers.push_back(std::move(laser));
  std::sort(c.lasers.begin(), c.lasers.end(), [](const LaserPart& a, const LaserPart& b) { return a.index < b.index; });
}

void set_stereo(StationCalibration& c, StereoPart stereo, std::optional<TurntablePart> turntable) {
  stereo.left.rotation.setIdentity();
  stereo.left.translation.setZero();
  stereo.turntable.reset();
  if (turntable) {
    TurntableAxis axis;
    axis.direction = turntable->axis_camera;
    axis.origin = turntable->origin_camera;
    PinholeCamera left = place_camera(stereo.left, axis);  // y from the left camera towards the axis
    // Turn the frame about the axis so that y runs from the middle between
    // the cameras instead: x_new = Rz(α) x_old puts that middle on −y.
    const Eigen::Vector3d right_centre = -stereo.right.rotation.transpose() * stereo.right.translation;  // left frame
    const Eigen::Vector3d middle = left.rotation.transpose() * (0.5 * right_centre - left.translation);
    const double alpha = -0.5 * std::numbers::pi - std::atan2(middle.y(), middle.x());
    left.rotation = left.rotation * turntable_rotation(alpha).transpose();
    stereo.left = left;
    stereo.turntable = std::move(turntable);
  }
  c.stereo = std::move(stereo);
}

std::pair<PinholeCamera, PinholeCamera> stereo_cameras(const StereoPart& stereo) {
  PinholeCamera right = stereo.right;
  right.rotation = stereo.right.rotation * stereo.left.rotation;
  right.translation = stereo.right.rotation * stereo.left.translation + stereo.right.translation;
  return {stereo.left, right};
}

std::string calibration_date() {
  std::time_t now = std::time(nullptr);
  if (const char* epoch = std::getenv("SOURCE_DATE_EPOCH"); epoch && *epoch) now = static_cast<std::time_t>(std::atoll(epoch));
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

}  // namespace scanstation::acquisition
