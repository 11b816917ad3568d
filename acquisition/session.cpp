#include "acquisition/session.h"

#include "acquisition/station_calibration.h"
#include "core/errors.h"
#include "core/image_codecs.h"
#include "core/io/file_access.h"
#include "core/io/json_document.h"
#include "core/io/station_geometry_json.h"
#include "core/log.h"

#include <Eigen/LU>
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fcntl.h>
#include <opencv2/core/utility.hpp>
#include <set>
#include <sstream>
#include <sys/stat.h>
#include <unistd.h>

namespace scanstation::acquisition {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr const char* kManifest = "manifest.json";
constexpr const char* kJournal = "journal.jsonl";
constexpr const char* kFormat = "scanstation-session";
constexpr int kFormatVersion = 1;

json vector_json(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }

// The rotation only when the object was turned (rows of the matrix), so a
// session of an upright object reads as before.
json placement_json(const ObjectPlacement& p) {
  json out = {{"scale", p.scale}, {"translation", vector_json(p.translation)}};
  if (!p.rotation.isIdentity(0.0))
    out["rotation"] = json::array({vector_json(p.rotation.row(0).transpose()),
                                   vector_json(p.rotation.row(1).transpose()),
                                   vector_json(p.rotation.row(2).transpose())});
  return out;
}

double seconds_of(drivers::Timestamp t) { return drivers::to_seconds(t); }

constexpr const char* kCameraNames[] = {"left", "right"};

json frame_json(const CapturedFrame& f, const std::string& file, bool stereo) {
  json frame = {{"file", file},
          {"laser", f.laser ? json(*f.laser) : json(nullptr)},
          {"sequence", f.frame.sequence},
          {"timestamp_s", seconds_of(f.frame.timestamp)},
          {"exposure_start_s", seconds_of(f.frame.exposure_start)},
          {"settled_s", seconds_of(f.settled)},
          {"discarded", f.discarded},
          {"dropped_before", f.frame.dropped_before}};
  if (stereo) {
    frame["camera"] = kCameraNames[f.camera == 1];
    frame["projector"] = f.projector;
  }
  return frame;
}

std::string os_error(const std::string& what, const fs::path& path) {
  return what + " " + path.string() + ": " + std::strerror(errno);
}

void write_fully(int fd, const std::string& text, const fs::path& path) {
  std::string_view rest = text;
  while (!rest.empty()) {
    const ssize_t n = ::write(fd, rest.data(), rest.size());
    if (n < 0) {
      if (errno == EINTR) continue;
      throw IoError(os_error("cannot append to", path));
    }
    rest.remove_prefix(static_cast<std::size_t>(n));
  }
  if (::fsync(fd) != 0) throw IoError(os_error("cannot flush", path));
}

int open_journal(const fs::path& path, bool truncate) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC | (truncate ? O_TRUNC : 0), 0644);
  if (fd < 0) throw IoError(os_error("cannot open the journal", path));
  return fd;
}

// ---- reading ---------------------------------------------------------------

json read_manifest_json(const fs::path& folder) {
  const fs::path path = folder / kManifest;
  if (!fs::exists(path))
    throw InvalidInput(path.string() + ": missing; " + folder.string() + " is not a scanstation session");
  const json manifest = io::read_json_document(path);
  if (!manifest.is_object()) throw FormatError(FileLocation::whole(path), "expected a JSON object");
  return manifest;
}

const json* find(const json& object, const char* key) {
  if (!object.is_object()) return nullptr;
  const auto it = object.find(key);
  return it == object.end() ? nullptr : &*it;
}

// The manifest's geometry; a camera that is missing, malformed or edited
// makes the session unreplayable, a laser plane only drops that laser.
void read_geometry(const json& manifest, const std::string& where, SessionContents& contents) {
  const json* geometry = find(manifest, "geometry");
  if (!geometry) throw InvalidInput(where + ": missing field \"geometry\": the session cannot be triangulated");
  const json* digests = find(manifest, "geometry_digest");
  TurntableGeometry& g = contents.manifest.geometry;
  if (const json* source = find(*geometry, "source"); source && source->is_string()) g.source = *source;
  if (const json* calibration = find(*geometry, "calibration")) g.calibration = *calibration;
  const json* camera = find(*geometry, "camera");
  if (!camera) throw InvalidInput(where + ": missing field \"geometry.camera\"");
  g.camera = pinhole_camera_from_json(*camera, where + ": geometry.camera");
  const json* camera_digest = digests ? find(*digests, "camera") : nullptr;
  if (!camera_digest) {
    contents.problems.push_back(where + ": missing field \"geometry_digest.camera\": the camera cannot be checked");
  } else if (*camera_digest != json_digest(*camera)) {
    throw InvalidInput(where + ": geometry.camera does not match geometry_digest.camera: the camera calibration was "
                       "changed after the scan; restore it, or replay with another calibration on purpose");
  }
  if (const json* right = find(*geometry, "right_camera")) {
    g.right_camera = pinhole_camera_from_json(*right, where + ": geometry.right_camera");
    const json* right_digest = digests ? find(*digests, "right_camera") : nullptr;
    if (!right_digest)
      contents.problems.push_back(where + ": missing field \"geometry_digest.right_camera\": the right camera cannot "
                                  "be checked");
    else if (*right_digest != json_digest(*right))
      throw InvalidInput(where + ": geometry.right_camera does not match geometry_digest.right_camera: the camera "
                         "calibration was changed after the scan; restore it, or replay with another calibration on "
                         "purpose");
  } else if (contents.manifest.rig == "stereo") {
    throw InvalidInput(where + ": missing field \"geometry.right_camera\": a stereo session needs both cameras");
  }
  const json* lasers = find(*geometry, "lasers");
  if (!lasers || !lasers->is_array()) throw InvalidInput(where + ": missing field \"geometry.lasers\" (an array)");
  const json* laser_digests = digests ? find(*digests, "lasers") : nullptr;
  for (std::size_t i = 0; i < lasers->size(); ++i) {
    const std::string field = "geometry.lasers[" + std::to_string(i) + "]";
    try {
      g.lasers.push_back(laser_plane_from_json((*lasers)[i], where + ": " + field));
    } catch (const InvalidInput& e) {
      g.lasers.emplace_back();
      contents.problems.push_back(std::string(e.what()) + "; laser " + std::to_string(i) + " skipped");
      continue;
    }
    if (!laser_digests || !laser_digests->is_array() || i >= laser_digests->size()) {
      contents.problems.push_back(where + ": missing field \"geometry_digest.lasers[" + std::to_string(i) +
                                  "]\": laser " + std::to_string(i) + " cannot be checked");
    } else if ((*laser_digests)[i] != json_digest((*lasers)[i])) {
      contents.problems.push_back(where + ": " + field + " does not match geometry_digest.lasers[" +
                                  std::to_string(i) + "]: the laser plane was changed after the scan; laser " +
                                  std::to_string(i) + " skipped");
      continue;
    }
    contents.lasers.push_back(static_cast<int>(i));
  }
}

void read_object(const json& manifest, const std::string& where, SessionContents& contents) {
  const json* object = find(manifest, "object");
  if (!object) {
    contents.problems.push_back(where + ": missing field \"object\": points stay in the platter frame");
    return;
  }
  SessionObject& o = contents.manifest.object;
  if (const json* name = find(*object, "name"); name && name->is_string()) o.name = *name;
  if (const json* mesh = find(*object, "mesh_file"); mesh && mesh->is_string()) o.mesh_file = *mesh;
  const json* placement = find(*object, "placement");
  if (!placement) return;
  const json* scale = find(*placement, "scale");
  if (!scale || !scale->is_number() || !(scale->get<double>() > 0))
    throw InvalidInput(where + ": object.placement.scale: expected a positive number");
  o.placement.scale = *scale;
  const json* translation = find(*placement, "translation");
  if (!translation || !translation->is_array() || translation->size() != 3 ||
      !std::all_of(translation->begin(), translation->end(), [](const json& v) { return v.is_number(); }))
    throw InvalidInput(where + ": object.placement.translation: expected an array of 3 numbers");
  for (int k = 0; k < 3; ++k) o.placement.translation[k] = (*translation)[static_cast<std::size_t>(k)];
  const json* rotation = find(*placement, "rotation");
  if (!rotation) return;
  const auto is_row = [](const json& r) {
    return r.is_array() && r.size() == 3 && std::all_of(r.begin(), r.end(), [](const json& v) { return v.is_number(); });
  };
  if (!rotation->is_array() || rotation->size() != 3 || !std::all_of(rotation->begin(), rotation->end(), is_row))
    throw InvalidInput(where + ": object.placement.rotation: expected 3 rows of 3 numbers");
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k)
      o.placement.rotation(i, k) = (*rotation)[static_cast<std::size_t>(i)][static_cast<std::size_t>(k)];
  const Eigen::Matrix3d& R = o.placement.rotation;
  if (!(R * R.transpose()).isIdentity(1e-9) || !(std::abs(R.determinant() - 1.0) < 1e-9))
    throw InvalidInput(where + ": object.placement.rotation: expected a rotation (orthonormal rows, determinant 1)");
}

void read_manifest(const fs::path& folder, SessionContents& contents) {
  const json manifest = read_manifest_json(folder);
  const std::string where = (folder / kManifest).string();
  SessionManifest& m = contents.manifest;
  const json* format = find(manifest, "format");
  if (!format || *format != kFormat)
    contents.problems.push_back(where + ": field \"format\" is not \"" + std::string(kFormat) + "\"; read anyway");
  const json* version = find(manifest, "version");
  if (!version || !version->is_number_integer())
    contents.problems.push_back(where + (version ? ": field \"version\": expected an integer, got " + version->dump()
                                                 : std::string(": missing field \"version\"")) +
                                "; read as version " + std::to_string(kFormatVersion));
  else if (version->get<long long>() > kFormatVersion)
    throw InvalidInput(where + ": version " + std::to_string(version->get<long long>()) +
                       ": this scanstation reads sessions up to version " + std::to_string(kFormatVersion) +
                       "; replay it with a newer scanstation");
  const json* rig = find(manifest, "rig");
  if (!rig || !rig->is_string()) throw InvalidInput(where + ": missing field \"rig\" (a string)");
  m.rig = *rig;
  if (m.rig != "turntable" && m.rig != "stereo")
    throw InvalidInput(where + ": rig \"" + m.rig + "\": expected \"turntable\" or \"stereo\"");
  const json* steps = find(manifest, "steps");
  if (!steps) throw InvalidInput(where + ": missing field \"steps\" (a positive integer)");
  if (!steps->is_number_integer() || steps->get<long long>() < 1 || steps->get<long long>() > 1 << 20)
    throw InvalidInput(where + ": field \"steps\": expected an integer from 1 to " + std::to_string(1 << 20) +
                       ", got " + steps->dump());
  m.steps = *steps;
  read_geometry(manifest, where, contents);
  if (const json* parameters = find(manifest, "parameters")) {
    std::vector<std::string> missing;
    if (m.rig == "stereo")
      m.stereo_parameters = stereo_scan_parameters_from_json(*parameters, where + ": parameters",
                                                             stereo_scan_defaults(), &missing);
    else
      m.parameters = laser_scan_parameters_from_json(*parameters, where + ": parameters", {}, &missing);
    for (const std::string& field : missing)
      contents.problems.push_back(where + ": missing field \"" + field.substr(where.size() + 2) +
                                  "\": the default is used");
  } else {
    contents.problems.push_back(where + ": missing field \"parameters\": the defaults are used");
  }
  read_object(manifest, where, contents);
  if (const json* station = find(manifest, "station")) {
    m.station = *station;
  } else {
    contents.problems.push_back(where + ": missing field \"station\"");
  }
  const json* software = find(manifest, "software");
  const json* software_version = software ? find(*software, "version") : nullptr;
  if (software_version && software_version->is_string()) {
    m.software_version = *software_version;
  } else {
    contents.problems.push_back(where + ": missing field \"software.version\"");
  }
}

// One step line of the journal, or a message saying what is wrong with it.
std::optional<SessionStep> parse_step(const json& line, const std::string& where, int planned, std::string& problem) {
  const json* step = find(line, "step");
  const json* angle = find(line, "angle_deg");
  const json* frames = find(line, "frames");
  const auto expected = [&](const json* field, const char* name, const char* what) {
    return where + (field ? std::string(": field \"") + name + "\": expected " + what + ", got " + field->dump()
                          : std::string(": missing field \"") + name + "\"");
  };
  if (!step || !step->is_number_integer()) return problem = expected(step, "step", "an integer"), std::nullopt;
  if (!angle || !angle->is_number() || !std::isfinite(angle->get<double>()) || std::abs(angle->get<double>()) > 1e6)
    return problem = expected(angle, "angle_deg", "a number of degrees"), std::nullopt;
  if (!frames || !frames->is_array()) return problem = expected(frames, "frames", "an array"), std::nullopt;
  // A step outside the turn the manifest plans cannot be a step of this scan.
  if (step->get<long long>() < 0 || step->get<long long>() >= planned)
    return problem = where + ": step " + step->dump() + ": expected 0 to " + std::to_string(planned - 1) +
                     " (the manifest plans " + std::to_string(planned) + " steps)",
           std::nullopt;
  SessionStep s;
  s.step = *step;
  s.angle_deg = *angle;
  double first = 0, last = 0;
  if (const json* start = find(line, "move_start_s"); start && start->is_number()) first = last = *start;
  for (std::size_t i = 0; i < frames->size(); ++i) {
    const json& f = (*frames)[i];
    const json* file = find(f, "file");
    const json* laser = find(f, "laser");
    if (!file || !file->is_string() || !laser || !(laser->is_null() || laser->is_number_integer()))
      return problem = where + ": frames[" + std::to_string(i) + "]: expected \"file\" and \"laser\"", std::nullopt;
    // Frames live in the session folder: a journal naming a file elsewhere
    // (an absolute path, a way up with "..") is not read.
    const fs::path name = file->get<std::string>();
    if (name.empty() || name.is_absolute() || std::find(name.begin(), name.end(), "..") != name.end())
      return problem = where + ": frames[" + std::to_string(i) + "].file \"" + name.string() +
                       "\": expected a path inside the session folder",
             std::nullopt;
    SessionFrame frame{*file, laser->is_null() ? std::nullopt : std::optional<int>(laser->get<int>())};
    if (const json* camera = find(f, "camera")) {
      if (*camera != kCameraNames[0] && *camera != kCameraNames[1])
        return problem = where + ": frames[" + std::to_string(i) + "].camera: expected \"left\" or \"right\"",
               std::nullopt;
      frame.camera = *camera == kCameraNames[1];
    }
    if (const json* projector = find(f, "projector"); projector && projector->is_boolean())
      frame.projector = *projector;
    s.frames.push_back(std::move(frame));
    if (const json* t = find(f, "timestamp_s"); t && t->is_number()) last = std::max(last, t->get<double>());
  }
  s.seconds = last - first;
  return s;
}

void read_journal(const fs::path& folder, SessionContents& contents) {
  const fs::path path = folder / kJournal;
  if (!fs::exists(path)) {
    contents.problems.push_back(path.string() + ": missing: no step was recorded");
    return;
  }
  const std::string text = io::read_file(path);
  std::set<int> recorded;  // a step recorded twice is no step of one scan
  std::size_t begin = 0, line_number = 0;
  while (begin < text.size()) {
    ++line_number;
    const std::size_t end = text.find('\n', begin);
    const std::string where = path.string() + ":" + std::to_string(line_number);
    if (end == std::string::npos) {
      contents.problems.push_back(where + ": truncated line (the scan stopped while writing it): ignored");
      break;
    }
    const json line = json::parse(text.begin() + static_cast<std::ptrdiff_t>(begin),
                                  text.begin() + static_cast<std::ptrdiff_t>(end), nullptr, false);
    begin = end + 1;
    contents.journal_end = begin;
    if (line.is_discarded() || !line.is_object()) {
      contents.problems.push_back(where + ": not a JSON object: ignored");
      continue;
    }
    const json* event = find(line, "event");
    if (!event || *event != "step") continue;
    std::string problem;
    auto step = parse_step(line, where, contents.manifest.steps, problem);
    if (step && !recorded.insert(step->step).second) {
      problem = where + ": step " + std::to_string(step->step) + " was recorded on an earlier line";
      step.reset();
    }
    if (step) {
      step->journal_line = line_number;
      contents.steps.push_back(std::move(*step));
    } else {
      contents.problems.push_back(problem + ": step ignored");
    }
  }
}

}  // namespace

std::string frame_file_name(int step, std::optional<int> laser) {
  char name[64];
  if (laser)
    std::snprintf(name, sizeof name, "frames/step_%04d_laser%d.png", step, *laser);
  else
    std::snprintf(name, sizeof name, "frames/step_%04d_off.png", step);
  return name;
}

std::string stereo_frame_file_name(int step, int camera, bool projector) {
  char name[64];
  std::snprintf(name, sizeof name, "frames/step_%04d_%s%s.png", step, kCameraNames[camera == 1],
                projector ? "_dots" : "");
  return name;
}

json to_json(const SessionManifest& m) {
  const json geometry = to_json(m.geometry);
  json laser_digests = json::array();
  for (const json& laser : geometry["lasers"]) laser_digests.push_back(json_digest(laser));
  json digests = {{"camera", json_digest(geometry["camera"])}, {"lasers", laser_digests}};
  if (geometry.contains("right_camera")) digests["right_camera"] = json_digest(geometry["right_camera"]);
  return {{"format", kFormat},
          {"version", kFormatVersion},
          {"software", {{"name", "scanstation"}, {"version", m.software_version}}},
          {"rig", m.rig},
          {"steps", m.steps},
          {"station", m.station},
          {"geometry", geometry},
          {"geometry_digest", digests},
          {"parameters", m.rig == "stereo" ? to_json(m.stereo_parameters) : to_json(m.parameters)},
          {"object",
           {{"name", m.object.name},
            {"mesh_file", m.object.mesh_file},
            {"placement", placement_json(m.object.placement)}}}};
}

json station_json(const drivers::StationDescription& d) {
  json lasers = json::array();
  for (const drivers::LaserRole& laser : d.lasers) lasers.push_back(laser.backend);
  const drivers::CameraFormat& format = d.camera.format;
  json station = {{"name", d.name},
                  {"file", d.source.string()},
                  {"camera", {{"backend", d.camera.backend},
                              {"pixel_format", drivers::pixel_format_name(format.format)},
                              {"width", format.size.width},
                              {"height", format.size.height}}},
                  {"lasers", lasers},
                  {"turntable", {{"backend", d.turntable.backend},
                                 {"steps_per_rev", d.turntable.stepper.steps_per_rev()}}},
                  {"usb_simulated", d.usb_simulated}};
  // What a calibration file must have been made for to replay the session
  // with it (acquisition/scan_calibration.h, replay_geometry).
  const StationFingerprint fingerprint = station_fingerprint(d);
  station["fingerprint"] = {{"hash", fingerprint.hash}, {"devices", fingerprint.devices}};
  if (d.right_camera) {
    const drivers::CameraFormat& right = d.right_camera->format;
    station["right_camera"] = {{"backend", d.right_camera->backend},
                               {"pixel_format", drivers::pixel_format_name(right.format)},
                               {"width", right.size.width},
                               {"height", right.size.height}};
  }
  if (d.projector) station["projector"] = d.projector->backend;
  if (!d.source.empty() && fs::exists(d.source)) station["toml"] = io::read_file(d.source);
  return station;
}

SessionContents read_session(const fs::path& folder) {
  SessionContents contents;
  contents.folder = folder;
  read_manifest(folder, contents);
  read_journal(folder, contents);
  return contents;
}

// ---- recording -------------------------------------------------------------

SessionRecorder::SessionRecorder(fs::path folder, SessionManifest manifest, int journal_fd, int steps_done)
    : folder_(std::move(folder)), manifest_(std::move(manifest)), journal_fd_(journal_fd), steps_done_(steps_done) {}

SessionRecorder::SessionRecorder(SessionRecorder&& other) noexcept
    : folder_(std::move(other.folder_)), manifest_(std::move(other.manifest_)), journal_fd_(other.journal_fd_),
      steps_done_(other.steps_done_), notes_(std::move(other.notes_)) {
  other.journal_fd_ = -1;
}

SessionRecorder::~SessionRecorder() {
  if (journal_fd_ >= 0) ::close(journal_fd_);
}

SessionRecorder SessionRecorder::create(const fs::path& folder, const SessionManifest& manifest,
                                        io::Overwrite overwrite) {
  if (folder.empty()) throw InvalidInput("an output folder name is empty");  // "" / "manifest.json" is the cwd's
  // Before anything is removed: --force with a file in the folder's place
  // failed inside the removal with the filesystem's own text.
  if (std::error_code error; fs::exists(folder, error) && !fs::is_directory(folder, error))
    throw InvalidInput(folder.string() + ": is a file, expected a session folder");
  if (overwrite == io::Overwrite::refuse && (fs::exists(folder / kManifest) || fs::exists(folder / kJournal)))
    throw InvalidInput(folder.string() + ": holds a session already; continue it with --resume, or use --force to "
                       "start over");
  if (overwrite == io::Overwrite::replace) {
    for (const char* name : {kJournal, "points.ply", "mesh.ply", "smooth.ply", "patches.json", "preview.png",
                             "report.json"})
      fs::remove(folder / name);
    for (const char* name : {"frames", "snapshots"}) fs::remove_all(folder / name);
  }
  io::make_folder(folder / "frames");
  io::write_file_atomically(folder / kManifest, to_json(manifest).dump(2) + "\n", overwrite);
  // The recorder holds the manifest as every reader will see it (numbers
  // after their round trip through the file), so the points it computes live
  // are the ones a replay computes, bit for bit.
  SessionContents written;
  read_manifest(folder, written);
  return SessionRecorder(folder, written.manifest, open_journal(folder / kJournal, true), 0);
}

SessionRecorder SessionRecorder::resume(const fs::path& folder) {
  const SessionContents contents = read_session(folder);
  for (std::size_t i = 0; i < contents.steps.size(); ++i)
    if (contents.steps[i].step != static_cast<int>(i))
      throw InvalidInput((folder / kJournal).string() + ":" + std::to_string(contents.steps[i].journal_line) +
                         ": step " + std::to_string(contents.steps[i].step) + " where step " + std::to_string(i) +
                         " was expected: the journal cannot be continued");
  // Cut whatever follows the last complete line (a line torn by the
  // interruption), so that new lines start on a line of their own.
  const fs::path journal = folder / kJournal;
  if (fs::exists(journal) && fs::file_size(journal) > contents.journal_end)
    fs::resize_file(journal, contents.journal_end);
  SessionRecorder recorder(folder, contents.manifest, open_journal(journal, false),
                           static_cast<int>(contents.steps.size()));
  recorder.notes_ = contents.problems;
  io::make_folder(folder / "frames");
  return recorder;
}

void SessionRecorder::append(const json& line) { write_fully(journal_fd_, line.dump() + "\n", folder_ / kJournal); }

void SessionRecorder::event(const std::string& name, const json& fields) {
  json line = {{"event", name}};
  line.update(fields);
  append(line);
}

void SessionRecorder::record(const CapturedStep& step) {
  json frames = json::array();
  const std::vector<int> png_options{cv::IMWRITE_PNG_COMPRESSION, 1};
  const bool stereo = manifest_.rig == "stereo";
  const auto file_of = [&](const CapturedFrame& frame) {
    return stereo ? stereo_frame_file_name(step.step, frame.camera, frame.projector) : frame_file_name(step.step, frame.laser);
  };
  // The step's frames compressed side by side (deflate is most of recording
  // a step), then written in order.
  std::vector<std::vector<unsigned char>> png(step.frames.size());
  std::vector<char> encoded(step.frames.size(), 0);
  cv::parallel_for_(cv::Range(0, static_cast<int>(step.frames.size())), [&](const cv::Range& range) {
    for (int k = range.start; k < range.end; ++k) {
      const auto i = static_cast<std::size_t>(k);
      encoded[i] = image::encode(".png", step.frames[i].frame.image, png[i], png_options);
    }
  });
  for (std::size_t k = 0; k < step.frames.size(); ++k) {
    const std::string file = file_of(step.frames[k]);
    if (!encoded[k]) throw IoError("cannot encode " + (folder_ / file).string() + " as PNG");
    io::write_file_atomically(folder_ / file, {reinterpret_cast<const char*>(png[k].data()), png[k].size()},
                              io::Overwrite::replace);
    frames.push_back(frame_json(step.frames[k], file, stereo));
  }
  append({{"event", "step"},
          {"step", step.step},
          {"angle_deg", step.angle_deg},
          {"move_start_s", seconds_of(step.move_start)},
          {"move_settled_s", seconds_of(step.move_settled)},
          {"exposure", step.exposure},
          {"gain", step.gain},
          {"frames", frames}});
  steps_done_ = step.step + 1;
}

Eigen::MatrixX3d own_coordinates(const Eigen::MatrixX3d& platter, const ObjectPlacement& placement) {
  const bool turned = !placement.rotation.isIdentity(0.0);
  if (placement.scale == 1.0 && placement.translation.isZero() && !turned) return platter;
  Eigen::MatrixX3d own = (platter.rowwise() - placement.translation.transpose()) / placement.scale;
  if (turned) own = (own * placement.rotation).eval();  // row by row: rotationᵀ · p
  return own;
}

Eigen::Vector3d own_coordinates(const Eigen::Vector3d& platter, const ObjectPlacement& placement) {
  return placement.rotation.transpose() * (platter - placement.translation) / placement.scale;
}

}  // namespace scanstation::acquisition
