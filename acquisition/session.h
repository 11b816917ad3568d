// A scanning session on disk: everything needed to process a scan again,
// recorded step by step so that an interruption loses nothing completed.
//
//   SESSION/manifest.json   rig, station, geometry (+ digests), parameters,
//                           object, software version; written once, atomically
//   SESSION/frames/         step_0007_off.png, step_0007_laser0.png, ...
//                           (lossless PNG, 8 or 16 bit as captured); a
//                           stereo rig's step_0007_left_dots.png,
//                           step_0007_right_dots.png (projector on) and
//                           step_0007_left.png (off: the colours)
//   SESSION/journal.jsonl   one JSON event per line: scan_started, step (angle,
//                           timestamps, exposure, gain, the frames and their
//                           laser), scan_stopped, scan_finished, scan_failed;
//                           each line is written after its frames, fsynced
//   SESSION/points.ply, mesh.ply, smooth.ply, patches.json, preview.png,
//   report.json, snapshots/   results (session_replay.h, station/)
//
// A step counts as recorded when its journal line is complete: its frames
// were on disk before the line was written.
#pragma once

#include "acquisition/laser_scan_parameters.h"
#include "acquisition/stereo_scan_parameters.h"
#include "acquisition/turntable_geometry.h"
#include "acquisition/turntable_scan.h"
#include "core/io/file_access.h"
#include "drivers/station_description.h"

#include <Eigen/Core>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace scanstation::acquisition {

/// Where the object's own coordinates (those of its mesh file) sit on the
/// platter: p_platter = scale · rotation · p_file + translation. Identity for
/// a real object; the simulator stands a mesh file on the platter (rotation:
/// which of its axes points up) and scales it to fit the rig.
struct ObjectPlacement {
  double scale = 1.0;
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
};

/// Points of the platter's object frame (#P by 3) in the object's own
/// coordinates: rotationᵀ (p − translation) / scale.
Eigen::MatrixX3d own_coordinates(const Eigen::MatrixX3d& platter, const ObjectPlacement& placement);
Eigen::Vector3d own_coordinates(const Eigen::Vector3d& platter, const ObjectPlacement& placement);

struct SessionObject {
  std::string name;       // built-in name, mesh file name, or what the operator typed
  std::string mesh_file;  // the mesh file simulated, "" otherwise
  ObjectPlacement placement;
};

/// rig  "turntable" (one camera, line lasers) or "stereo" (two cameras,
///      geometry.right_camera, an optional projector); the manifest's
///      "parameters" are `parameters` or `stereo_parameters` accordingly
struct SessionManifest {
  std::string rig = "turntable";
  int steps = 0;                   // steps per turn planned
  nlohmann::json station;          // the station description as opened
  TurntableGeometry geometry;
  LaserScanParameters parameters;
  StereoScanParameters stereo_parameters = stereo_scan_defaults();
  SessionObject object;
  std::string software_version;
};

/// The manifest document, with "format": "scanstation-session", "version": 1
/// and "geometry_digest": {"camera": D, ["right_camera": D,] "lasers": [D, ...]}
/// (json_digest of each part as written).
nlohmann::json to_json(const SessionManifest& manifest);

/// A session being recorded. Frames go through io::write_file_atomically
/// (flushed, renamed into place); each journal line is appended with one
/// write() and fsync()ed.
class SessionRecorder {
 public:
  /// Starts a new session in `folder`; refuses a folder that already holds a
  /// session (manifest or journal) unless `overwrite` is replace, which
  /// clears the old session's files first.
  static SessionRecorder create(const std::filesystem::path& folder, const SessionManifest& manifest,
                                io::Overwrite overwrite);
  /// Continues an interrupted session: reads its manifest and journal, cuts
  /// a torn last journal line, and continues after the last recorded step.
  /// Throws InvalidInput when the folder holds no session or its steps are
  /// not a gap-free run from step 0.
  static SessionRecorder resume(const std::filesystem::path& folder);

  SessionRecorder(SessionRecorder&&) noexcept;
  SessionRecorder& operator=(SessionRecorder&&) = delete;
  ~SessionRecorder();

  const SessionManifest& manifest() const { return manifest_; }
  const std::filesystem::path& folder() const { return folder_; }
  /// Steps recorded so far (they are steps 0 .. steps_done − 1).
  int steps_done() const { return steps_done_; }
  /// Problems found in the journal when resuming (a cut line, ...).
  const std::vector<std::string>& notes() const { return notes_; }

  /// Writes the step's frames, then its journal line.
  void record(const CapturedStep& step);
  /// Appends a non-step event {"event": name, ...fields}.
  void event(const std::string& name, const nlohmann::json& fields);

 private:
  SessionRecorder(std::filesystem::path folder, SessionManifest manifest, int journal_fd, int steps_done);
  void append(const nlohmann::json& line);

  std::filesystem::path folder_;
  SessionManifest manifest_;
  int journal_fd_ = -1;
  int steps_done_ = 0;
  std::vector<std::string> notes_;
};

/// A frame of a recorded step: file relative to the session folder and the
/// laser lit (none for the laser-off frame); of a stereo step, the camera
/// (0 left, 1 right) and whether the projector was lit.
struct SessionFrame {
  std::string file;
  std::optional<int> laser;
  int camera = 0;
  bool projector = false;
};

struct SessionStep {
  int step = 0;
  double angle_deg = 0;
  std::size_t journal_line = 0;  // 1-based
  double seconds = 0;            // from the start of the move to the last frame's timestamp
  std::vector<SessionFrame> frames;
};

/// What a session folder holds, as far as it is readable.
/// steps       every complete, well-formed step line of the journal, in order
/// lasers      lasers whose geometry is intact (digest matches, well formed)
/// problems    each damage found: the file, line or field, what is wrong and
///             what is done about it ("... skipped")
/// journal_end byte offset just past the last complete journal line
struct SessionContents {
  std::filesystem::path folder;
  SessionManifest manifest;
  std::vector<SessionStep> steps;
  std::vector<int> lasers;
  std::vector<std::string> problems;
  std::size_t journal_end = 0;
};

/// Reads a session folder. Throws InvalidInput naming the file and field when
/// nothing can be replayed: no manifest, a manifest that is not JSON, a
/// missing or malformed rig, steps or camera, a camera that does not match its
/// recorded digest. Damage that leaves something replayable (a laser plane
/// edited or malformed, missing optional fields, a torn or malformed journal
/// line) is listed in `problems`.
SessionContents read_session(const std::filesystem::path& folder);

/// What the manifest records of a station: name, file (and its text),
/// each role's backend, the camera format, and its calibration fingerprint
/// ("fingerprint": {"hash", "devices"}, station_calibration.h).
nlohmann::json station_json(const drivers::StationDescription& station);

/// "frames/step_0007_off.png", "frames/step_0007_laser1.png".
std::string frame_file_name(int step, std::optional<int> laser);

/// A stereo step's frame: "frames/step_0007_left_dots.png" (camera 0,
/// projector on), "frames/step_0007_right.png" (camera 1, projector off).
std::string stereo_frame_file_name(int step, int camera, bool projector);

}  // namespace scanstation::acquisition
