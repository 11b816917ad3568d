// The pose of a chessboard in the camera frame from its detected corners and a
// calibrated camera (OpenCV solvePnP): the common first step of the laser
// plane and turntable axis calibrations.
#pragma once

#include "core/station_geometry.h"

#include <opencv2/core.hpp>

#include <vector>

namespace scanstation::acquisition {

/// x_camera = rotation · x_board + translation; board points as
/// chessboard_points() (inner corner (0, 0) at the origin, z = 0 on the board,
/// square size as unit of length); rms  reprojection RMS of the corners (px).
struct BoardPose {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  double rms = 0;

  Eigen::Vector3d normal() const { return rotation.col(2); }
  Eigen::Vector3d to_camera(const Eigen::Vector3d& board) const { return rotation * board + translation; }
};

/// corners        the corners find_chessboard() returned for one view
/// camera         intrinsics and distortion (its pose is not used)
/// Planar start (IPPE) refined by Levenberg–Marquardt on the reprojection error.
/// Throws InvalidInput when the corner count does not match inner_corners.
BoardPose board_pose(const std::vector<cv::Point2f>& corners, cv::Size inner_corners, double square_size,
                     const PinholeCamera& camera);

/// Where a view's board lies in the image: the projected outline of the
/// squares, widened by `margin` squares on every side (0 = the outer edge of
/// the pattern).
std::vector<cv::Point2f> board_outline(const BoardPose& pose, cv::Size inner_corners, double square_size,
                                       const PinholeCamera& camera, double margin = 0.0);

}  // namespace scanstation::acquisition
