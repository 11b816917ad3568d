// The boundary grown while the table turns (issue 8; thesis Chapter 5 applied
// step by step): every step's points, all lasers together, go into one
// incremental constriction, so a live view always has a closed genus-0
// boundary through every point received so far.
#pragma once

#include "acquisition/session.h"
#include "acquisition/laser_triangulation.h"
#include "core/io/file_access.h"
#include "reconstruct/incremental_constriction.h"

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

namespace scanstation::station {

/// A fingerprint (64-bit FNV-1a) of a stream of step clouds: every
/// coordinate's bits, in order. Two runs fed the same points in the same
/// order have the same digest.
class StreamDigest {
 public:
  void add(const std::vector<acquisition::LaserScanPoints>& clouds);
  std::uint64_t value() const { return hash_; }

 private:
  std::uint64_t hash_ = 14695981039346656037ull;
};

/// margin          rings re-opened around each batch (IncrementalConstriction)
/// camera_centre   where the camera that saw the points sits, in the station
///                 frame: each step's points are fed with it turned back by
///                 the step's angle as their viewpoint, so the live boundary
///                 carves their lines of sight first; none: plain constriction
/// snapshot_every  K > 0: after every K-th step fed, the current boundary is
///                 written to snapshot_folder/boundary-step-NNNN.ply (NNNN the
///                 step's index), in the object's own coordinates (placement)
struct LiveBoundaryOptions {
  int margin = 2;
  std::optional<Eigen::Vector3d> camera_centre;
  int snapshot_every = 0;
  std::filesystem::path snapshot_folder;
  acquisition::ObjectPlacement placement;
  io::Overwrite overwrite = io::Overwrite::refuse;
};

/// What one step did to the live boundary.
/// points          distinct points so far; boundary_faces  triangles of the
/// constricted boundary; all_on_boundary  every point so far is a vertex of it
struct LiveStep {
  int step = 0;
  double angle_deg = 0;
  Eigen::Index step_points = 0, points = 0, boundary_faces = 0;
  bool all_on_boundary = false;
  std::size_t pending = 0;
  /// How far the step's repair reached (BatchStats): the Delaunay cells it
  /// looked at, the boundary triangles it re-decided (all of them when the
  /// repair was not local), and whether it re-constricted everything.
  std::size_t cells_touched = 0, faces_changed = 0;
  bool wider_repair = false;
  double seconds = 0;
  std::optional<std::filesystem::path> snapshot;
};

/// The "boundary" progress event: {step, angle_deg, points, boundary_faces,
/// all_on_boundary, pending, cells_touched, faces_changed, wider_repair,
/// seconds[, snapshot]}.
nlohmann::json to_json(const LiveStep& step);

class LiveBoundary {
 public:
  explicit LiveBoundary(LiveBoundaryOptions options = {});

  /// Feeds one step's clouds (platter object frame, one per laser).
  LiveStep add_step(int step, double angle_deg, const std::vector<acquisition::LaserScanPoints>& clouds);

  const IncrementalConstriction& constriction() const { return constriction_; }
  /// Of every point fed so far (StreamDigest).
  std::uint64_t digest() const { return digest_.value(); }
  int steps() const { return steps_; }
  /// Re-decided cells crossed by a line of sight, over all steps (BatchStats).
  std::size_t sight_line_cells() const { return sight_line_cells_; }
  double seconds() const { return seconds_; }

 private:
  LiveBoundaryOptions options_;
  IncrementalConstriction constriction_;
  StreamDigest digest_;
  int steps_ = 0;
  std::size_t sight_line_cells_ = 0;
  double seconds_ = 0;
};

}  // namespace scanstation::station
