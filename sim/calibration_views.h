// Calibration views on the simulator: the chessboard standing on the platter
// at the poses a careful operator would choose, rendered with area-averaged
// pixels (one ray per pixel centre aliases the board's edges and biases the
// corners: fx 0.6% off; 2× supersampling brings it within 0.2%). The
// calibrate command captures them through the simulated station's devices
// (sim/calibration_station.h); render_board() renders one directly.
#pragma once

#include "sim/scene_renderer.h"

#include <cstdint>
#include <vector>

namespace scanstation::sim {

/// A board with inner_corners (columns × rows) of `square` size, its middle at
/// `middle` (object frame), rows running down and tilted back by `tilt`
/// radians from vertical, facing −y (the rig camera's side).
ChessboardTarget standing_board(int columns, int rows, double square, double tilt, const Point3& middle);

/// Height of the board's lowest inner corner (above the platter top, z = 0).
double lowest_corner_height(const ChessboardTarget& board);

/// One view of a calibration run: the board's placement and the turntable angle.
struct BoardPlacement {
  ChessboardTarget board;
  double angle = 0;
};

/// Varied tilts, turns, heights and sideways shifts reaching the image edges
/// (camera intrinsics and distortion), for the rig of
/// turntable_laser_rig(80, 60, ...): 12 views.
std::vector<BoardPlacement> camera_placements(int columns, int rows, double square);

/// One board placement, off the axis, seen at turntable angles from −60° to
/// +60° in `views` steps (turntable axis).
std::vector<BoardPlacement> turntable_placements(int columns, int rows, double square, int views = 9);

/// The board near the axis at several depths, tilts and turns, so the light
/// planes of the rig's lasers (vertical, through the axis) cross it (laser planes).
std::vector<BoardPlacement> laser_placements(int columns, int rows, double square);

/// The frames of one placement: laser off, and one per laser of `scene` with
/// only that laser on (when `with_lasers`), each rendered at `supersampling`×
/// and area-averaged to the camera's size; sensor noise from `seed`.
struct BoardFrames {
  cv::Mat laser_off;
  std::vector<cv::Mat> laser_on;
};
BoardFrames render_board(Scene scene, const BoardPlacement& placement, const PinholeCamera& camera, bool with_lasers,
                         std::uint64_t seed, int supersampling = 2);

}  // namespace scanstation::sim
