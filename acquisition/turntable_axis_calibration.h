// Turntable axis calibration: the axis direction and the platter origin from
// the calibration board standing on the platter, seen at several turntable
// angles. Every inner corner of the board travels on a circle about the
// axis: the circles' common normal is the axis direction, their common centre
// line the axis, and the commanded angles fix which way "up" points. The
// result places the camera in the station frame (core/station_geometry.h).
#pragma once

#include "acquisition/board_pose.h"
#include "core/station_geometry.h"

#include <vector>

namespace scanstation::acquisition {

/// In the camera frame:
/// direction   unit axis; the platter turns counter-clockwise about it for
///             growing commanded angles (the station's +z, "up")
/// origin      the platter origin: on the axis, at the top of the platter
/// rms, max    distances of the board corners to their fitted circles (station units)
/// angle_rms   RMS difference of the board's measured turns (about the axis,
///             relative to the first view) from the commanded ones (radians)
/// measured_angles  the board's turn in each view relative to the first (radians)
struct TurntableAxis {
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  double rms = 0, max = 0, angle_rms = 0;
  std::vector<double> measured_angles;
};

/// poses      board poses (board_pose()) of the same board at different turntable angles
/// angles     the commanded turntable angle of each pose (radians)
/// lowest_corner_height  height of the board's lowest inner corner above the
///            platter top (station units): the board does not show where the platter is
/// Throws InvalidInput for fewer than 3 poses, angles spanning less than 5°,
/// a board that did not turn with the platter, or mismatched sizes.
TurntableAxis calibrate_turntable_axis(const std::vector<BoardPose>& poses, const std::vector<double>& angles,
                                       cv::Size inner_corners, double square_size, double lowest_corner_height);

/// `camera` (intrinsics) placed in the station frame the axis defines: z the
/// axis, origin the platter origin, and y pointing from the camera's side of
/// the axis towards the axis (the camera sits on the −y side, as in
/// sim::turntable_laser_rig), x = y × z.
PinholeCamera place_camera(const PinholeCamera& camera, const TurntableAxis& axis);

}  // namespace scanstation::acquisition
